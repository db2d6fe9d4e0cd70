# test_dispdev.sh: the offscreen display devices from the command line: -dispdev osmesa and
# egl start their back-end quietly; opengl, openglpbuffer and win pick the best one and say
# which; VMD's OpenGL displays turn depth cueing on; a text session draws `render snapshot`
# on demand; a device that cannot start names the reason and one that works; the example
# renders its PNG. Each back-end is skipped where it is not built.
. "$(dirname "$0")/lib.sh"
cd "$scratch"
script='render snapshot s.ppm; puts "[display get depthcue] [file size s.ppm]"'
out=$(echo "$script" | $MOLSCOPE -dispdev text 2>&1)
case "$out" in *"not built"*|*"no offscreen OpenGL device"*)
    skip "offscreen OpenGL" "$out"; rm -rf "$scratch"; exit 0;;
esac
size=$((512 * 512 * 3 + 15))      # VMD's 512 x 512 and the PPM header "P6\n512 512\n255\n"
for dev in osmesa egl; do
    out=$(echo "$script" | $MOLSCOPE -dispdev $dev 2>&1)
    case "$out" in
    *"not built"*) skip "-dispdev $dev" "not built into this molscope";;
    *) expect_eq "-dispdev $dev starts quietly, turns depth cueing on and draws" "$out" "on $size";;
    esac
done
for dev in opengl openglpbuffer WIN; do
    out=$(echo "$script" | $MOLSCOPE -dispdev $dev 2>&1)
    expect_match "-dispdev $dev says which device it uses" "$(echo "$out" | head -1)" \
        "molscope: -dispdev $dev: using [eo][gs]*OpenGL*"
    expect_eq "-dispdev $dev draws" "$(echo "$out" | tail -1)" "on $size"
done
out=$(echo "$script" | $MOLSCOPE -dispdev text 2>&1)
expect_eq "a text session draws render snapshot on demand (depth cueing stays off)" "$out" "off $size"
out=$(echo "$script" | $MOLSCOPE -dispdev opengl -size 64 48 2>/dev/null)
expect_eq "-size sets the image size" "$out" "on $((64 * 48 * 3 + 13))"

# EGL with no vendor library cannot start: the reason, a device that works, then text.
out=$(echo "$script" | __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json $MOLSCOPE -dispdev egl 2>&1)
case "$out" in
*"not built"*) skip "egl that cannot start" "EGL not built";;
*) expect_match "egl that cannot start: reason and a working device" "$out" \
       "molscope: -dispdev egl: egl: no display gives an OpenGL 3.3 core context (*); -dispdev osmesa works here; using text*off $size";;
esac

# The README's main job: the example renders 1tii to a PNG.
out=$($MOLSCOPE -dispdev opengl -e "$MS_SRCDIR/scripts/example.tcl" -args "$MS_TEST_DATA/1tii.pdb" \
      "$scratch/ex.png" 2>&1 < /dev/null); rc=$?
expect_match "the example renders 1tii" "$rc:$out" "0:*Atoms:5684*rendered $scratch/ex.png (800x600, *"
expect_eq "the example's image is a PNG" "$(head -c 8 "$scratch/ex.png" | od -An -c | tr -d ' ')" '211PNG\r\n032\n'
rm -rf "$scratch"
