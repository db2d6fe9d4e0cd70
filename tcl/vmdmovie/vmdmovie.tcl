# vmdmovie.tcl: VMD's MovieMaker (`package require vmdmovie`) for batch scripts, molscope's
# own code on molscope's movie engine (tcl/movie.tcl, `movie make`): a script sets the
# ::MovieMaker:: variables and calls ::MovieMaker::buildmovie, and the frames are handed out
# over MPI, encoded while they are rendered and resumed after a killed job, as `movie make`
# does. doc/vmdmovie.md lists the variables, movie types and formats, and what is not done.
package provide vmdmovie 1.9

namespace eval ::MovieMaker {
    # where and under what name (frames <workdir>/<basename>.%05d.png, the movie beside)
    variable workdir [expr {[info exists ::env(TMPDIR)] && $::env(TMPDIR) ne "" ?
                            $::env(TMPDIR) : "/tmp"}]
    variable basename untitled
    # what movie: rockandroll rotation trajectory trajectoryrock userdefined
    # (trajectoryrotation: molscope's trajectory turning as the rotation movie does)
    variable movietype rockandroll
    variable movieduration 10     ;# seconds, for all types but the trajectories
    variable numframes 1          ;# frames of the movie (set by buildmovie unless a script set it)
    variable anglestep 1          ;# degrees per frame of the last rotation movie (read only)
    variable rotateangle 180      ;# degrees turned by a rotation movie
    variable rotateaxis y         ;# molscope: the axis of rotation movies (x, y or z)
    variable rockangle 30         ;# molscope: the amplitude of the rocking movies, degrees
    variable trjstart 0
    variable trjend 1             ;# beyond the last frame: the last frame
    variable trjstep 1
    # how
    variable framerate 24
    variable renderer snapshot    ;# snapshot libtachyon tachyon, a `render list` name, dryrun
    variable imgformat tga        ;# VMD's intermediate image format: rgb makes SGI frames
                                  ;# (basename.%05d.rgb), any other PNG ones
    variable movieformat ppmtompeg
    variable bitrate 8000000
    variable presmooth 0
    variable prescale 0
    variable scalefactor 0.5
    variable prelabel 0
    variable labeltext {Produced by molscope}
    variable labelsize 7
    variable labelrow auto
    variable labelcolor gray
    variable labelbgcolor transparent
    variable cleanfiles 1
    # progress, as VMD's window shows it
    variable statusmsg Ready
    variable statusstep 0
    variable statussteps 0
    variable statusfrac 0
    variable statustotal 0
    variable usercancel 0
    # the frame of a user-defined movie: scripts attach a write trace to it
    variable userframe 0
    # molscope: set when a script writes numframes itself (buildmovie then keeps it)
    variable numframes_given 0
    variable setting_numframes 0
    # the view when the movie started (rockandroll sets each frame from it)
    variable start_pose {}
    variable types {rockandroll rotation trajectory trajectoryrock trajectoryrotation userdefined}
    # movieformat -> {codec extension}, or {frames extension}; VMD's names and molscope's
    variable formats {
        ppmtompeg {mpeg1 .mpg}  ffmpeg {mpeg1 .mpg}  videomachmpeg {mpeg1 .mpg}
        sgimpeg1v {mpeg1 .mpg}  mpeg2 {mpeg2 .mpg}   mpeg4 {mpeg4 .mp4}
        videomachavi {mpeg4 .avi}  sgiavi {mpeg4 .avi}  h264 {h264 .mp4}
        quicktime {h264 .mov}   sgiqt {h264 .mov}    imgif {gif .gif}
        pngframes {frames .png} targaframes {frames .tga} ppmframes {frames .ppm}
        bmpframes {frames .bmp}  rgbframes {frames .rgb}
    }
}

# A script that writes numframes chooses the frame count itself.
trace add variable ::MovieMaker::numframes write [list apply {{args} {
    if {!$::MovieMaker::setting_numframes} { set ::MovieMaker::numframes_given 1 }
}}]

# ---------------------------------------------------------------- checks

proc ::MovieMaker::fail {what} { error "::MovieMaker::buildmovie: $what" }

proc ::MovieMaker::number {name min {int 0}} {
    set v [set ::MovieMaker::$name]
    set ok [expr {$int ? [string is integer -strict $v] : [string is double -strict $v]}]
    if {!$ok || $v < $min} {
        fail "$name: expected [expr {$int ? {an integer} : {a number}}] of at least $min, got '$v'"
    }
    return $v
}

proc ::MovieMaker::choice {name choices} {
    set v [set ::MovieMaker::$name]
    if {$v ni $choices} { fail "$name: unknown value '$v': must be [join $choices {, }]" }
    return $v
}

# The render method of `renderer`: VMD's names, any of `render list`, or dryrun.
proc ::MovieMaker::render_method {} {
    variable renderer
    set map {snapshot snapshot libtachyon TachyonInternal tachyon Tachyon}
    set r [expr {[dict exists $map [string tolower $renderer]] ?
                 [dict get $map [string tolower $renderer]] : $renderer}]
    if {$r eq "dryrun"} { return dryrun }
    set known [render list]
    if {[lsearch -exact -nocase $known $r] < 0} {
        fail "renderer: '$renderer' is not a render method here (snapshot, libtachyon,\
              tachyon, dryrun, or one of [join $known {, }])"
    }
    return $r
}

# The trajectory frames: first, last and count from trjstart, trjend, trjstep.
proc ::MovieMaker::trajectory_range {} {
    set top [molinfo top]
    if {$top < 0 || [molinfo $top get numframes] < 1} {
        fail "movietype $::MovieMaker::movietype: no molecule with frames is loaded"
    }
    set nf [molinfo $top get numframes]
    set first [number trjstart 0 1]
    set end [number trjend 0 1]
    set step [number trjstep 1 1]
    if {$first >= $nf} {
        fail "trjstart $first: the top molecule has $nf frame[expr {$nf == 1 ? "" : "s"}]"
    }
    set end [expr {min($end, $nf - 1)}]
    if {$end < $first} { fail "trjend $end is before trjstart $first" }
    set n [expr {($end - $first) / $step + 1}]
    list $first [expr {$first + ($n - 1) * $step}] $n
}

# The frame count of the types that last movieduration seconds.
proc ::MovieMaker::timed_frames {} {
    variable numframes
    if {$::MovieMaker::numframes_given} { return [number numframes 1 1] }
    set n [expr {int(round([number movieduration 0] * [number framerate 1]))}]
    if {$n < 1} { fail "movieduration $::MovieMaker::movieduration at $::MovieMaker::framerate frames/s makes no frame" }
    return $n
}

# ---------------------------------------------------------------- the plan

# `movie make` options of the movie type, and the frame count.
proc ::MovieMaker::type_options {type} {
    variable rotateangle
    set axis [choice rotateaxis {x y z}]
    set rock [number rockangle 0]
    switch -- $type {
        rotation {
            set n [timed_frames]
            set angle [number rotateangle -1e9]
            set o [list -type rotation -axis $axis -angle $angle]
            set ::MovieMaker::anglestep [expr {double($angle) / $n}]
        }
        rockandroll {
            set n [timed_frames]
            set o [list -type user -proc ::MovieMaker::rockandroll_frame]
        }
        userdefined {
            set n [timed_frames]
            set o [list -type user -proc ::MovieMaker::user_frame]
        }
        default {
            lassign [trajectory_range] first last n
            set t [dict get {trajectory trajectory trajectoryrock {trajectory rock}
                             trajectoryrotation {trajectory rotation}} $type]
            set o [list -type $t -first $first -last $last -axis $axis]
            if {$type eq "trajectoryrock"} { lappend o -angle $rock }
            if {$type eq "trajectoryrotation"} { lappend o -angle [number rotateangle -1e9] }
        }
    }
    list $n [concat $o -frames $n]
}

# The size of the frames: the display's, scaled by scalefactor when prescale is on.
proc ::MovieMaker::frame_size {} {
    lassign [display get size] w h
    if {$::MovieMaker::prescale} {
        set f [number scalefactor 0.01]
        set w [expr {max(1, int(round($w * $f)))}]
        set h [expr {max(1, int(round($h * $f)))}]
    }
    list $w $h
}

proc ::MovieMaker::warn_unsupported {} {
    foreach {v what} {presmooth "image smoothing" prelabel "text labels"} {
        if {[set ::MovieMaker::$v]} {
            puts stderr "MovieMaker: $v ($what) is not done by molscope; the frames are as rendered"
        }
    }
}

# ---------------------------------------------------------------- frames

# A user-defined frame: userframe is written, so the scripts' traces set the scene.
proc ::MovieMaker::user_frame {i} {
    set ::MovieMaker::userframe $i
}

# Rock and roll: from the starting view, a figure of eight (an XY lemniscate): about y by
# rockangle * sin(phase), about x by rockangle/2 * sin(2 phase).
proc ::MovieMaker::rockandroll_frame {i} {
    variable start_pose
    set ph [expr {2 * acos(-1) * $i / double($::MovieMaker::numframes)}]
    ::molscope::movie::pose $start_pose
    rotate y by [expr {$::MovieMaker::rockangle * sin($ph)}]
    rotate x by [expr {$::MovieMaker::rockangle * 0.5 * sin(2 * $ph)}]
}

# dryrun: every frame's scene set in turn, nothing rendered; the view and frames put back.
# For the movie types whose frames are procedures (userdefined, rockandroll).
proc ::MovieMaker::dryrun {type n} {
    variable start_pose
    if {$type ni {userdefined rockandroll}} {
        fail "renderer dryrun: only for the userdefined and rockandroll movie types, not $type"
    }
    set frames {}
    foreach m [molinfo list] { lappend frames $m [molinfo $m get frame] }
    for {set i 0} {$i < $n} {incr i} {
        set ::MovieMaker::statusfrac $i
        switch -- $type {
            userdefined { user_frame $i }
            rockandroll { rockandroll_frame $i }
        }
        display update
    }
    ::molscope::movie::pose $start_pose
    foreach {m f} $frames { if {$m in [molinfo list]} { molinfo $m set frame $f } }
    return [dict create frames $n rendered 0 video ""]
}

# Frames (of the engine's format, from) written again in the format of ext (targaframes
# ...), by rank 0.
proc ::MovieMaker::convert_frames {base n from ext} {
    if {[::molscope::movie::parallel_rank] != 0} return
    for {set i 0} {$i < $n} {incr i} {
        set frame [format "%s.%05d.%s" $base $i $from]
        ::molscope::movie::convert $frame [file rootname $frame]$ext
        if {$::MovieMaker::cleanfiles} { file delete $frame }
    }
}

# The engine's frame format: rgb (SGI) when imgformat or the frames asked for say so.
proc ::MovieMaker::frame_format {codec ext} {
    if {$codec eq "frames"} { return [expr {$ext eq ".rgb" ? "rgb" : "png"}] }
    expr {[string tolower $::MovieMaker::imgformat] eq "rgb" ? "rgb" : "png"}
}

# ---------------------------------------------------------------- buildmovie

# Make the movie the ::MovieMaker:: variables describe. Collective under MPI: every rank
# calls it. Returns `movie make`'s dict (frames rendered reused ranks video ...).
proc ::MovieMaker::buildmovie {} {
    variable start_pose
    set type [choice movietype $::MovieMaker::types]
    set method [render_method]
    set format [string tolower $::MovieMaker::movieformat]
    if {![dict exists $::MovieMaker::formats $format]} {
        fail "movieformat: unknown format '$::MovieMaker::movieformat': must be\
              [join [dict keys $::MovieMaker::formats] {, }]"
    }
    lassign [dict get $::MovieMaker::formats $format] codec ext
    lassign [type_options $type] n opts
    set ::MovieMaker::setting_numframes 1
    set ::MovieMaker::numframes $n
    set ::MovieMaker::setting_numframes 0
    set start_pose [::molscope::movie::pose]
    set ::MovieMaker::statustotal $n
    set ::MovieMaker::statusmsg Rendering
    if {$method eq "dryrun"} {
        set r [dryrun $type $n]
        set ::MovieMaker::statusmsg Ready
        return $r
    }
    warn_unsupported
    set base [file join $::MovieMaker::workdir $::MovieMaker::basename]
    set fmt [frame_format $codec $ext]
    lappend opts -basename $base -renderer $method -size [frame_size] \
        -fps [number framerate 1] -bitrate [number bitrate 1000 1] -format $fmt
    if {$codec ne "frames"} {
        lappend opts -video $base$ext -codec $codec -keepframes [expr {!$::MovieMaker::cleanfiles}]
    }
    set r [movie make {*}$opts]
    if {$codec eq "frames" && $ext ne ".$fmt"} { convert_frames $base $n $fmt $ext }
    set ::MovieMaker::statusfrac $n
    set ::MovieMaker::statusmsg Completed
    return $r
}
