# exectool.tcl: VMD's exectool package (doc/exectool.md): finding an external program
# (::ExecTool::find) and running it (::ExecTool::exec). molscope has no GUI, so where VMD
# would ask the user for a program's location (-interactive), a message on stderr says what
# was looked for and where, and the answer is "not found".
package provide exectool 1.2

namespace eval ::ExecTool {
    namespace export find exec
    # The usual places programs live besides PATH.
    variable places {/usr/local/bin /usr/bin /bin /opt/local/bin /usr/sbin /sbin /opt/bin}
}

# An executable regular file?
proc ::ExecTool::runnable {path} {
    expr {$path ne "" && [file isfile $path] && [file executable $path]}
}

# ::ExecTool::find ?-interactive? ?-description text? ?-path path? name
# The full path of program name: -path first (a file, or a folder holding name), then PATH,
# then the usual places and $HOME/bin. "" when it is not found.
proc ::ExecTool::find {args} {
    variable places
    if {![llength $args]} {
        error "::ExecTool::find: wrong # args: usage: ::ExecTool::find ?-interactive? ?-description text? ?-path path? name"
    }
    set name [lindex $args end]
    set interactive 0
    set description ""
    set path ""
    set opts [lrange $args 0 end-1]
    for {set i 0} {$i < [llength $opts]} {incr i} {
        set w [lindex $opts $i]
        switch -- $w {
            -interactive { set interactive 1 }
            -description - -path {
                if {$i + 1 >= [llength $opts]} { error "::ExecTool::find: no value for option \"$w\"" }
                set [string range $w 1 end] [lindex $opts [incr i]]
            }
            default { error "::ExecTool::find: unknown option \"$w\": must be -interactive, -description, or -path" }
        }
    }
    set tries {}
    if {$path ne ""} { lappend tries $path [file join $path $name] }
    if {[file pathtype $name] ne "relative" || [string first / $name] >= 0} { lappend tries $name }
    foreach t $tries { if {[::ExecTool::runnable $t]} { return [file normalize $t] } }
    if {[string first / $name] < 0} {
        set found [auto_execok $name]
        if {[llength $found] == 1 && [::ExecTool::runnable [lindex $found 0]]} { return [lindex $found 0] }
        set dirs $places
        if {[info exists ::env(HOME)]} { lappend dirs [file join $::env(HOME) bin] }
        foreach d $dirs {
            set t [file join $d $name]
            if {[::ExecTool::runnable $t]} { return $t }
        }
    }
    if {$interactive} {
        set what [expr {$description ne "" ? "$name ($description)" : $name}]
        puts stderr "exectool: $what was not found in PATH or the usual places, and there is no display to ask for it: put it on PATH or give its location with -path"
    }
    return ""
}

# ::ExecTool::exec args: Tcl's exec with the same words (pipes, redirections, &); returns
# the program's output, or fails as exec does.
proc ::ExecTool::exec {args} {
    uplevel 1 [list ::exec {*}$args]
}
