# test_manpage.sh: molscope(1) says what `molscope -h` says: the same options as the
# usage and as doc/commands.md's command-line table; it is installed by `make install`,
# and man renders it without warnings.
. "$(dirname "$0")/lib.sh"
man1="$MS_SRCDIR/doc/molscope.1"
# The option words of each source, one a line, sorted and unique.
from_usage() { "$MOLSCOPE" -h | grep -E '^  -' | sed -E 's/  +[^-].*$//' |
    grep -oE '(^  |, )--?[a-z<>]+' | sed -E 's/^(  |, )//' | sort -u; }
from_man() { awk 'prev == ".TP" {print} {prev = $0}' "$man1" |
    sed -E 's/^\.B[IR]? //; s/\\-/-/g; s/^- type/-<type>/; s/"[^"]*"//g' |
    grep -oE '(^|, *| )--?[a-z<>]+' | sed -E 's/^[ ,]*//' | sort -u; }
from_doc() { sed -n '/^## Command line/,/^## /p' "$MS_SRCDIR/doc/commands.md" | grep '^| `' | cut -d'|' -f2 |
    grep -oE '`--?[a-z<>]+' | tr -d '`' | sort -u; }
usage=$(from_usage | tr '\n' ' ')
expect_match "the usage lists the options" "$usage" "*-dispdev*-eofexit*"
expect_eq "molscope(1) has the options of molscope -h" "$(from_man | tr '\n' ' ')" "$usage"
expect_eq "doc/commands.md has the options of molscope -h" "$(from_doc | tr '\n' ' ')" "$usage"
for s in NAME SYNOPSIS DESCRIPTION OPTIONS ENVIRONMENT FILES "EXIT STATUS" EXAMPLES; do
    if grep -q "^\.SH \"\?$s\"\?\$" "$man1"; then pass "molscope(1) has $s"; else fail "molscope(1) has $s" "missing"; fi
done
# Every MOLSCOPE_* variable the program reads is documented in ENVIRONMENT.
vars=$(grep -rhoE '(getenv|ms_env_flag|env_number|env_choice)\("MOLSCOPE_[A-Z_]+"' \
       "$MS_SRCDIR/src" "$MS_SRCDIR/plugins" | grep -oE 'MOLSCOPE_[A-Z_]+' | sort -u)
missing=""
for v in $vars; do grep -q "$v" "$man1" || missing="$missing $v"; done
expect_eq "molscope(1) documents every MOLSCOPE_ variable the sources read" "$missing" ""
if command -v man > /dev/null && command -v groff > /dev/null; then
    warn=$(LC_ALL=C.UTF-8 MANWIDTH=80 man --warnings -l "$man1" 2>&1 > /dev/null)
    expect_eq "man renders molscope(1) without warnings" "$warn" ""
else
    skip "man renders molscope(1)" "man-db is not installed"
fi
prefix="$scratch/prefix"
if make -s -C "$MS_BUILDDIR" install-man prefix="$prefix" > "$scratch/install.log" 2>&1 &&
   [ -f "$prefix/share/man/man1/molscope.1" ]; then
    pass "make install puts molscope.1 in share/man/man1"
    if command -v man > /dev/null; then
        out=$(MANPATH="$prefix/share/man" MANWIDTH=80 man molscope 2>&1 | tr -s ' ' | head -20)
        expect_match "man molscope shows the page" "$out" "*molscope*VMD scripts*"
    fi
else
    fail "make install puts molscope.1 in share/man/man1" "$(tail -3 "$scratch/install.log")"
fi
rm -rf "$scratch"
