# movie.tcl: the `movie` command, molscope's movie maker in the spirit of VMD's MovieMaker:
# trajectory, rotation, rock and user-defined frames, any render method, frames named
# <basename>.%05d.png (or .rgb, SGI, as VMD's movie maker writes them with -format rgb), an
# MP4 encoded as the frames complete, and the same script in one
# process or under mpirun. doc/movies.md is the user's guide.
#
#   movie make ?-option value ...?   make a movie; returns a dict of what was done and the
#                                     phase times (every rank of an MPI job must call it)
#   movie types                      the frame types
#
# Each frame sets the scene from its index alone (trajectory: `animate goto`; rotation and
# rock: the view saved when the movie starts, turned by the frame's angle), so any rank can
# render any frame and a movie made on N ranks equals the one made in one process. The
# machinery (which frames are missing, handing them out across the ranks, checking and
# renaming each frame, the encoder, progress) is C: ::molscope::movie::run (cmd_movie.c).

namespace eval ::molscope::movie {
    namespace export movie
    # When this library was loaded: the end of "script loading" in the phase times.
    variable library_loaded [expr {[clock microseconds] / 1e6}]
    variable types {trajectory rotation rock user}
    # The movie being made (set by make, read by the frame procs).
    variable job
    # Render methods that write a scene file rather than an image; Tachyon's is rendered
    # by the tachyon program, the others cannot make movie frames.
    variable scene_exporters {Tachyon POV3 Wavefront Raster3D RenderMan STL VRML-2 X3D}
}

proc ::molscope::movie::usage {} {
    return "movie make ?-basename path? ?-video file.mp4? ?-type trajectory|rotation|rock|user\
            (or a list of them)? ?-frames N? ?-first F? ?-last L? ?-axis x|y|z? ?-angle deg?\
            ?-proc command? ?-renderer method? ?-size W H? ?-fps F? ?-codec C? ?-crf Q? ?-preset P?\
            ?-bitrate B? ?-keepframes 0|1? ?-format png|rgb?\
            ?-progress auto|on|off?"
}

proc ::molscope::movie::movie {args} {
    if {[llength $args] == 0} { error "movie: usage: [usage] | movie types" }
    set sub [lindex $args 0]
    switch -nocase -- $sub {
        make { return [make {*}[lrange $args 1 end]] }
        types { return $::molscope::movie::types }
        default { error "movie: unknown subcommand \"$sub\": must be make or types" }
    }
}

# ---------------------------------------------------------------- options

proc ::molscope::movie::int_option {name value min} {
    if {![string is integer -strict $value] || $value < $min} {
        error "movie make: $name: expected an integer of at least $min, got '$value'"
    }
    return $value
}

# The options as a dict with defaults filled in; errors name the option and the value.
proc ::molscope::movie::parse {arglist} {
    set o [dict create -basename "" -video "" -type "" -frames "" -first 0 -last end \
               -axis y -angle "" -proc "" -renderer snapshot -size "" -fps 30 -crf 18 \
               -preset veryfast -keepframes 1 -progress auto -codec h264 -bitrate 8000000 \
               -format png]
    for {set i 0} {$i < [llength $arglist]} {incr i} {
        set k [lindex $arglist $i]
        if {![dict exists $o $k]} {
            error "movie make: unknown option '$k': must be [join [dict keys $o] {, }]"
        }
        if {$i + 1 >= [llength $arglist]} { error "movie make: $k needs a value" }
        set v [lindex $arglist [incr i]]
        # -size W H or -size {W H}
        if {$k eq "-size" && [llength $v] == 1 && $i + 1 < [llength $arglist]} {
            set v [list $v [lindex $arglist [incr i]]]
        }
        dict set o $k $v
    }
    return $o
}

proc ::molscope::movie::check_size {size} {
    if {$size eq ""} { return [display get size] }
    lassign $size w h
    if {[llength $size] != 2 || ![string is integer -strict $w] || ![string is integer -strict $h]
        || $w < 1 || $h < 1 || $w > 16384 || $h > 16384} {
        error "movie make: -size: expected a width and a height from 1 to 16384 pixels,\
               got '$size'"
    }
    return [list $w $h]
}

proc ::molscope::movie::check_renderer {name} {
    variable scene_exporters
    set known [render list]
    set i [lsearch -exact -nocase $known $name]
    if {$i < 0} {
        error "movie make: -renderer: no render method '$name' (render list: [join $known {, }])"
    }
    set name [lindex $known $i]
    if {$name eq "Tachyon"} {
        if {[tachyon_program] eq ""} {
            error "movie make: -renderer Tachyon: the tachyon program is not there (install\
                   it, or set TACHYON_BIN)"
        }
    } elseif {$name in $scene_exporters} {
        error "movie make: -renderer $name: it writes a scene file, not an image (use\
               snapshot, Tachyon or an image renderer)"
    }
    return $name
}

proc ::molscope::movie::tachyon_program {} {
    if {[info exists ::env(TACHYON_BIN)] && $::env(TACHYON_BIN) ne ""} {
        return [lindex [auto_execok $::env(TACHYON_BIN)] 0]
    }
    return [lindex [auto_execok tachyon] 0]
}

# The video's codec and bitrate from the options (fps checked already): MPEG-1 and MPEG-2
# know only the MPEG frame rates.
proc ::molscope::movie::check_codec {o fps} {
    set codec [string tolower [dict get $o -codec]]
    set codecs {h264 mpeg1 mpeg2 mpeg4 gif}
    if {$codec ni $codecs} {
        error "movie make: -codec: unknown codec '$codec': must be [join $codecs {, }]"
    }
    set rates {23.976 24 25 29.97 30 50 59.94 60}
    if {$codec in {mpeg1 mpeg2} && [lsearch -real $rates $fps] < 0} {
        error "movie make: -fps $fps: $codec video knows only the MPEG frame rates\
               ([join $rates {, }])"
    }
    set bitrate [dict get $o -bitrate]
    if {![string is wide -strict $bitrate] || $bitrate < 1000 || $bitrate > 1000000000} {
        error "movie make: -bitrate: expected bits per second from 1000 to 1000000000,\
               got '$bitrate'"
    }
    list $codec $bitrate
}

# Frame types, frames and the trajectory range from the options.
proc ::molscope::movie::plan_frames {o} {
    variable types
    set top [molinfo top]
    set nf [expr {$top < 0 ? 0 : [molinfo $top get numframes]}]
    set type [dict get $o -type]
    if {$type eq ""} { set type [expr {$nf > 1 ? "trajectory" : "rotation"}] }
    foreach t $type {
        if {$t ni $types} {
            error "movie make: -type: unknown type '$t': must be [join $types {, }] or a list of them"
        }
    }
    if {"user" in $type && [dict get $o -proc] eq ""} {
        error "movie make: -type user needs -proc <command> (called with the frame index)"
    }
    set first 0
    set last -1
    if {"trajectory" in $type} {
        if {$nf < 1} { error "movie make: -type trajectory: no molecule with frames is loaded" }
        set first [int_option -first [dict get $o -first] 0]
        set last [dict get $o -last]
        if {$last eq "end"} { set last [expr {$nf - 1}] }
        set last [int_option -last $last $first]
        if {$last >= $nf} {
            error "movie make: -last $last: the top molecule has $nf frame[expr {$nf == 1 ? "" : "s"}] (0 to [expr {$nf - 1}])"
        }
    }
    set n [dict get $o -frames]
    if {$n eq ""} {
        if {"trajectory" in $type} { set n [expr {$last - $first + 1}] } elseif {"user" in $type} {
            error "movie make: -type user needs -frames <count>"
        } else { set n 120 }
    }
    set n [int_option -frames $n 1]
    set axis [string tolower [dict get $o -axis]]
    if {$axis ni {x y z}} { error "movie make: -axis: expected x, y or z, got '$axis'" }
    set angle [dict get $o -angle]
    if {$angle eq ""} { set angle [expr {"rotation" in $type ? 360.0 : 30.0}] }
    if {![string is double -strict $angle]} {
        error "movie make: -angle: expected degrees, got '$angle'"
    }
    list $type $n $first $last $axis $angle
}

# ---------------------------------------------------------------- frames

# Set the scene for frame i of the movie in job (from i alone).
proc ::molscope::movie::set_scene {i} {
    variable job
    dict with job {
        if {"trajectory" in $type} {
            set f $first
            if {$frames > 1} {
                set f [expr {$first + int(round(double($i) * ($last - $first) / ($frames - 1)))}]
            }
            animate goto $f
        }
        if {"rotation" in $type || "rock" in $type} {
            ::molscope::movie::pose $pose
            if {"rotation" in $type} {
                rotate $axis by [expr {$angle * $i / double($frames)}]
            }
            if {"rock" in $type} {
                rotate $axis by [expr {$angle * sin(2 * acos(-1) * $i / double($frames))}]
            }
        }
        if {$userproc ne ""} { uplevel #0 [list {*}$userproc $i] }
    }
}

# ::molscope::movie::run's frame callback: render frame i into the file tmp.
proc ::molscope::movie::frame {i tmp} {
    variable job
    set_scene $i
    set r [dict get $job renderer]
    if {$r eq "Tachyon"} {
        set dat $tmp.dat
        render Tachyon $dat
        # tachyon's names: PNG, and RGB for SGI's format
        set fmt [expr {[string tolower [file extension $tmp]] eq ".rgb" ? "RGB" : "PNG"}]
        set rc [catch {exec [tachyon_program] -aasamples [render aasamples Tachyon] \
                           -format $fmt -o $tmp $dat >/dev/null 2>@1} msg]
        file delete $dat
        if {$rc || ![file exists $tmp]} { error "tachyon wrote no image: $msg" }
    } else {
        render $r $tmp
    }
}

# ---------------------------------------------------------------- make

proc ::molscope::movie::make {args} {
    variable job
    set o [parse $args]
    lassign [plan_frames $o] type n first last axis angle
    set renderer [check_renderer [dict get $o -renderer]]
    lassign [check_size [dict get $o -size]] w h
    set video [dict get $o -video]
    set base [dict get $o -basename]
    if {$base eq ""} {
        if {$video eq ""} { error "movie make: give -basename (frames) or -video (or both)" }
        set base [file rootname $video]
    }
    if {[string index $base end] eq "/" || [file tail $base] eq ""} {
        error "movie make: -basename $base: give a folder and a file name prefix, such as\
               out/frame"
    }
    if {$video ne "" && [file extension $video] eq ""} {
        error "movie make: -video $video: the name needs an extension that names the format\
               (.mp4, .mkv, .mov ...)"
    }
    set keep [dict get $o -keepframes]
    if {$keep ni {0 1}} { error "movie make: -keepframes: expected 0 or 1, got '$keep'" }
    set fps [dict get $o -fps]
    if {![string is double -strict $fps] || $fps <= 0 || $fps > 1000} {
        error "movie make: -fps: expected frames per second above 0 and at most 1000, got '$fps'"
    }
    set crf [dict get $o -crf]
    if {![string is integer -strict $crf] || $crf < 0 || $crf > 51} {
        error "movie make: -crf: expected a quality from 0 (best) to 51, got '$crf'"
    }
    set preset [dict get $o -preset]
    set presets {ultrafast superfast veryfast faster fast medium slow slower veryslow placebo}
    if {$preset ni $presets} {
        error "movie make: -preset: expected one of x264's presets ([join $presets {, }]),\
               got '$preset'"
    }
    lassign [check_codec $o $fps] codec bitrate
    set format [string tolower [dict get $o -format]]
    if {$format ni {png rgb}} {
        error "movie make: -format: unknown frame format '[dict get $o -format]': must be png or rgb"
    }
    set progress [dict get [dict create auto -1 on 1 off 0] \
                      [string tolower [dict get $o -progress]]]

    # What to put back afterwards: the view, every molecule's frame, the display size.
    set saved_size [display get size]
    set saved_frames {}
    foreach m [molinfo list] { lappend saved_frames $m [molinfo $m get frame] }
    set pose [pose]
    set job [dict create type $type frames $n first $first last $last axis $axis \
                 angle $angle pose $pose userproc [dict get $o -proc] renderer $renderer]
    display resize $w $h
    set rc [catch {run ::molscope::movie::frame -basename $base -frames $n -width $w \
                       -height $h -video $video -fps $fps -crf $crf -preset $preset -keepframes $keep \
                       -codec $codec -bitrate $bitrate -format $format \
                       -progress $progress -started [started] \
                       -scriptdone $::molscope::movie::library_loaded} result opts]
    display resize {*}$saved_size
    pose $pose
    foreach {m f} $saved_frames {
        if {$m in [molinfo list] && $f >= 0} { molinfo $m set frame $f }
    }
    if {$rc} { return -options $opts $result }
    if {$progress != 0 && [parallel_rank] == 0} { summary $result $w $h $renderer $base.*.$format }
    return $result
}

proc ::molscope::movie::parallel_rank {} {
    if {[catch {parallel noderank} r]} { return 0 }
    return $r
}

# Rank 0's account of a finished movie: what was made and the phase times of the paper's
# Table 3 (script loading, state loading, geometry and rendering, total).
proc ::molscope::movie::summary {r w h renderer frames} {
    dict with r {
        set out "movie: $frames frames of ${w}x$h with $renderer on $ranks\
                 rank[expr {$ranks > 1 ? "s" : ""}]: $rendered rendered, $reused reused;"
        if {$video ne ""} { append out " video $video" } else { append out " frames $frames" }
        puts stderr $out
        if {$note ne ""} { puts stderr "movie: $note" }
        puts stderr [format "movie: phases (rank 0 / slowest rank): script loading %.2f / %.2f s,\
                             state loading %.2f / %.2f s, geometry and rendering %.2f s,\
                             total %.2f s" $script $script_max $state $state_max $render $total]
        set fpm [expr {$render > 0 ? $rendered * 60.0 / $render : 0}]
        puts stderr [format "movie: %.1f frames/min; in frame calls %.2f s on the busiest rank,\
                             %.2f s on all; encoding after the last frame %.2f s" \
                         $fpm $busy_max $busy_sum $encode_tail]
    }
}

interp alias {} ::movie {} ::molscope::movie::movie
