# bench_scale.tcl: issue 23's stages in one molscope process (run by bench_scale.sh):
#   molscope -dispdev text -e bench_scale.tcl -args <system.js> <image>
# load, QuickSurf of everything (radius scale 1.0, isovalue 0.5, grid 2 A, quality 0,
# coloured by chain), NewCartoon of the first copy (segname 0000), and a 1920x1080
# TachyonInternal render with shadows and ambient occlusion. After each stage a line
#   STAGE <name> <wall s> <cpu s> <VmHWM bytes> <VmRSS bytes> <user s> <system s>
# and at the end, the bytes of every structure (::molscope::memory) as
#   MEM <key> <bytes>
lassign $argv file image

# CPU seconds of this process so far, all threads: {user system} (utime and stime of
# /proc/self/stat).
proc cpu_now {} {
    set f [open /proc/self/stat]
    set s [read $f]
    close $f
    set fields [split [string range $s [expr {[string last ")" $s] + 2}] end]]
    return [list [expr {[lindex $fields 11] / 100.0}] [expr {[lindex $fields 12] / 100.0}]]
}

# VmHWM and VmRSS of this process in bytes (from /proc, so that builds before
# ::molscope::memory can be measured the same way).
proc vm {} {
    set f [open /proc/self/status]
    set s [read $f]
    close $f
    regexp {VmHWM:\s+(\d+)} $s -> hwm
    regexp {VmRSS:\s+(\d+)} $s -> rss
    return [list [expr {$hwm * 1024}] [expr {$rss * 1024}]]
}

proc stage {name script} {
    set t0 [clock microseconds]
    set c0 [cpu_now]
    uplevel 1 $script
    set wall [expr {([clock microseconds] - $t0) / 1e6}]
    lassign [cpu_now] u1 s1
    lassign $c0 u0 s0
    set user [expr {$u1 - $u0}]
    set sys [expr {$s1 - $s0}]
    lassign [vm] hwm rss
    puts [format "STAGE %s %.2f %.2f %d %d %.2f %.2f" $name $wall [expr {$user + $sys}] $hwm $rss \
              $user $sys]
    flush stdout
}

stage load {
    set m [mol new $file waitfor all]
    puts "ATOMS [molinfo $m get numatoms]"
}
stage quicksurf {
    mol modstyle 0 $m QuickSurf 1.0 0.5 2.0 0
    mol modcolor 0 $m Chain
    mol modmaterial 0 $m AOChalky
    mol modselect 0 $m all
    mol repinfo $m 0
}
stage newcartoon {
    mol representation NewCartoon
    mol color Chain
    mol selection "segname 0000"
    mol addrep $m
    mol repinfo $m 1
}
stage render {
    display resize 1920 1080
    display shadows on
    display ambientocclusion on
    display projection orthographic
    axes location off
    render TachyonInternal $image
}
if {[info commands ::molscope::memory] ne ""} {
    foreach {key bytes} [::molscope::memory] {puts "MEM $key $bytes"}
}
quit
