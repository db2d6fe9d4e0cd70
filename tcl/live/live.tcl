# live.tcl: what the live view's page reads and runs through the session's own commands
# (doc/live.md). The server sources it when `display live on` starts:
#   ::molscope::live::session   the molecules, their reps, the trajectory and display
#                               settings as one JSON object, read with molinfo, mol,
#                               animate, display, axes, color and material queries only
#   ::molscope::live::python    run Python typed in the page's console (gopython -command),
#                               what it prints becoming the command's output
namespace eval ::molscope::live {
    variable pycode ""
}

# A JSON string.
proc ::molscope::live::str {s} {
    set map [list \\ \\\\ \" \\\" \n \\n \r \\r \t \\t]
    set s [string map $map $s]
    # the other control characters
    regsub -all {[\x00-\x1f]} $s {} s
    return "\"$s\""
}

proc ::molscope::live::bool {b} {
    expr {[string is true -strict $b] ? "true" : "false"}
}

# One rep of molecule m as a JSON object.
proc ::molscope::live::rep {m i} {
    lassign [molinfo $m get [list "rep $i" "color $i" "selection $i" "material $i"]] \
        style color sel mat
    return [format {{"name":%s,"style":%s,"color":%s,"selection":%s,"material":%s,"shown":%s}} \
                [str [mol repname $m $i]] [str $style] [str $color] [str $sel] [str $mat] \
                [bool [mol showrep $m $i]]]
}

proc ::molscope::live::molecule {m} {
    lassign [molinfo $m get {name numatoms numframes frame top active drawn numreps}] \
        name natoms nframes frame top active drawn nreps
    set reps {}
    for {set i 0} {$i < $nreps} {incr i} { lappend reps [rep $m $i] }
    return [format {{"id":%d,"name":%s,"atoms":%d,"frames":%d,"frame":%d,"top":%s,"active":%s,"shown":%s,"reps":[%s]}} \
                $m [str $name] $natoms $nframes $frame [bool $top] [bool $active] [bool $drawn] \
                [join $reps ,]]
}

proc ::molscope::live::display_json {} {
    set bg [color Display Background]
    set items [list \
        projection [str [display get projection]] \
        depthcue [bool [display get depthcue]] \
        ambientocclusion [bool [display get ambientocclusion]] \
        shadows [bool [display get shadows]] \
        axes [str [axes location]] \
        background [str $bg] \
        size "\[[join [display get size] ,]\]"]
    set out {}
    foreach {k v} $items { lappend out "\"$k\":$v" }
    return "{[join $out ,]}"
}

proc ::molscope::live::strings {l} {
    set out {}
    foreach s $l { lappend out [str $s] }
    return "\[[join $out ,]\]"
}

proc ::molscope::live::session {} {
    set mols {}
    foreach m [molinfo list] { lappend mols [molecule $m] }
    set anim [format {{"speed":%s,"style":%s,"skip":%d}} [animate speed] \
                  [str [animate style]] [animate skip]]
    set lists [format {"materials":%s,"colors":%s,"axes":%s} [strings [material list]] \
                   [strings [colorinfo colors]] [strings [axes locations]]]
    return [format {{"molecules":[%s],"animate":%s,"display":%s,%s}} [join $mols ,] $anim \
                [display_json] $lists]
}

# Python from the page: compiled as the interactive prompt does for a single line (so an
# expression's value is printed), as a module otherwise; its prints go to Tcl's stdout,
# where the console's capture sees them.
proc ::molscope::live::python {code} {
    variable pycode $code
    gopython -command {
import io as _io, contextlib as _cl, _molscope as _ms
_src = _ms.call("set", "::molscope::live::pycode")
_buf = _io.StringIO()
try:
    with _cl.redirect_stdout(_buf):
        exec(compile(_src, "<live>", "single" if "\n" not in _src.strip() else "exec"), globals())
finally:
    if _buf.getvalue(): _ms.call("puts", "-nonewline", _buf.getvalue())
    del _src, _buf
}
}
