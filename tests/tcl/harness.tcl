# harness.tcl: the Tcl-level test harness. molscope runs it with -e and the test file as its
# argument; each check prints "PASS: name", "FAIL: name: why" or "SKIP: name: why".
#
#   test name script expected      the script's result equals expected (string compare)
#   test_match name script glob    the result matches a glob pattern
#   test_near name script expected ?tol?
#                                  numbers (or lists of numbers) agree within tol (1e-4)
#   test_error name script glob    the script fails with a message matching glob
#   skip name why
# Variables: ::data (the test data folder), ::out (a scratch folder for output files).

set ::data $env(MS_TEST_DATA)
set ::out $env(MS_TEST_OUT)
set ::t_file [file rootname [file tail [lindex $argv 0]]]

proc ::t_report {status name {why ""}} {
    if {$why eq ""} {
        puts "$status: $::t_file: $name"
    } else {
        # one line per report: newlines in messages would split it
        puts "$status: $::t_file: $name: [string map {\n { | }} $why]"
    }
}

proc test {name script expected} {
    if {[catch {uplevel #0 $script} res opts]} {
        ::t_report FAIL $name "error: $res"
    } elseif {$res ne $expected} {
        ::t_report FAIL $name "got {$res}, expected {$expected}"
    } else {
        ::t_report PASS $name
    }
}

proc test_match {name script pattern} {
    if {[catch {uplevel #0 $script} res]} {
        ::t_report FAIL $name "error: $res"
    } elseif {![string match $pattern $res]} {
        ::t_report FAIL $name "got {$res}, expected to match {$pattern}"
    } else {
        ::t_report PASS $name
    }
}

proc ::t_flatten {l} {
    set out {}
    foreach e $l {
        if {[llength $e] > 1} { lappend out {*}[::t_flatten $e] } else { lappend out $e }
    }
    return $out
}

proc ::t_near {a b tol} {
    set a [::t_flatten $a]
    set b [::t_flatten $b]
    if {[llength $a] != [llength $b]} { return 0 }
    foreach x $a y $b {
        if {![string is double -strict $x] || ![string is double -strict $y]} {
            if {$x ne $y} { return 0 }
        } elseif {abs($x - $y) > $tol * max(1.0, abs($y))} {
            return 0
        }
    }
    return 1
}

proc test_near {name script expected {tol 1e-4}} {
    if {[catch {uplevel #0 $script} res]} {
        ::t_report FAIL $name "error: $res"
    } elseif {![::t_near $res $expected $tol]} {
        ::t_report FAIL $name "got {$res}, expected {$expected} within $tol"
    } else {
        ::t_report PASS $name
    }
}

proc test_error {name script pattern} {
    if {[catch {uplevel #0 $script} res]} {
        if {[string match $pattern $res]} {
            ::t_report PASS $name
        } else {
            ::t_report FAIL $name "error {$res} does not match {$pattern}"
        }
    } else {
        ::t_report FAIL $name "no error (result {$res}), expected one matching {$pattern}"
    }
}

proc skip {name why} { ::t_report SKIP $name $why }

# The bytes of a file, whole.
proc read_bytes {path} {
    set f [open $path rb]
    set b [read $f]
    close $f
    return $b
}

# The text of a file, whole (the platform's line endings and encoding).
proc read_text {path} {
    set f [open $path]
    set t [read $f]
    close $f
    return $t
}

# Write bytes to a file (replacing it); returns the path.
proc write_bytes {path bytes} {
    set f [open $path wb]
    puts -nonewline $f $bytes
    close $f
    return $path
}

# Whether two files hold the same bytes.
proc same_file {a b} { expr {[read_bytes $a] eq [read_bytes $b]} }

# A binary PPM (P6, 8 bits): {width height pixels}; an error when the file is not one.
proc read_ppm {file} {
    set data [read_bytes $file]
    if {![regexp {^P6\s+(\d+)\s+(\d+)\s+(\d+)\s} $data head w h max]} { error "$file is not a PPM" }
    list $w $h [string range $data [string length $head] end]
}

# The {r g b} of pixel (x, y) of a read_ppm image, rows from the top.
proc pixel {img x y} {
    lassign $img w h d
    binary scan $d @[expr {3 * ($y * $w + $x)}]cu3 rgb
    return $rgb
}

# Whether two lists of numbers agree element by element within tol.
proc near3 {a b tol} {
    foreach x $a y $b { if {abs($x - $y) > $tol} { return 0 } }
    return 1
}

# A colour (by id or name) as VMD's 0-255 integers.
proc rgb255 {id} { lmap v [colorinfo rgb $id] { expr {int(round($v * 255))} } }

if {[catch {source [lindex $argv 0]} err]} {
    ::t_report FAIL "(file)" "script error: $err [string range $::errorInfo 0 300]"
}
quit
