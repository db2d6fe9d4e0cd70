/* font.c: molscope's own stroke font for text in exported scenes (VMD draws text as line
 * strokes the same way). Glyphs live on a grid 4 units wide with capitals 6 units tall;
 * each is a list of polylines, points written as two digits "xy" with y counted from 2 below
 * the baseline, polylines separated by '|'. Lower case letters have their own glyphs (x-height
 * 4 units, descenders to 2 below the baseline), so text keeps its case. */
#include "config.h"
#include "render/export.h"

#include <math.h>
#include <string.h>

static const char *const glyphs[95] = {
    /* ' ' */ "", /* ! */ "2824|2322", /* " */ "1817|3837", /* # */ "1317|3337|0444|0646",
    /* $ */ "473818070615354443321203|2129", /* % */ "0248|0607|3233",
    /* & */ "42070818271603122244", /* ' */ "2827", /* ( */ "38272332", /* ) */ "18272312",
    /* * */ "1535|2426|1436|1634", /* + */ "1535|2426", /* , */ "2321", /* - */ "1535",
    /* . */ "2223", /* / */ "0248",
    /* 0 */ "183847433212030718|1337", /* 1 */ "172822|1232", /* 2 */ "07183847460242",
    /* 3 */ "07183847463515|354443321203", /* 4 */ "32380444", /* 5 */ "480805354443321203",
    /* 6 */ "473818070312324344351504", /* 7 */ "084822",
    /* 8 */ "183847463515060718|1504031232434435", /* 9 */ "4515060718384743321203",
    /* : */ "2322|2625", /* ; */ "2625|2321", /* < */ "371533", /* = */ "1434|1636",
    /* > */ "173513", /* ? */ "07183847462524|2322", /* @ */ "183847433212030718|3525",
    /* A */ "022842|1535", /* B */ "02083847463505|3544433202", /* C */ "4738180703123243",
    /* D */ "02082846442202", /* E */ "48080242|0535", /* F */ "480802|0535",
    /* G */ "47381807031232434525", /* H */ "0208|4248|0545", /* I */ "1232|2228|1838",
    /* J */ "4843321203", /* K */ "0208|4804|1542", /* L */ "080242", /* M */ "0208254842",
    /* N */ "02084248", /* O */ "183847433212030718", /* P */ "02083847463505",
    /* Q */ "183847433212030718|2442", /* R */ "02083847463505|2542",
    /* S */ "473818070615354443321203", /* T */ "0848|2822", /* U */ "080312324348",
    /* V */ "082248", /* W */ "0812253248", /* X */ "0842|4802", /* Y */ "082548|2522",
    /* Z */ "08480242",
    /* [ */ "38181232", /* \ */ "0842", /* ] */ "18383212", /* ^ */ "162836", /* _ */ "0242",
    /* ` */ "1827",
    /* a..z: x-height 4 units, descenders 2 below the baseline */
    /* a */ "4642|4536160503123243", /* b */ "0802|0516364543321203",
    /* c */ "4536160503123243", /* d */ "4842|4536160503123243", /* e */ "04444536160503123243",
    /* f */ "22273848|1636", /* g */ "4641301001|4536160504133344", /* h */ "0802|0516364542",
    /* i */ "2622|2827", /* j */ "26211001|2827", /* k */ "0802|4603|1442", /* l */ "18282332",
    /* m */ "0602|05162522|25364542", /* n */ "0602|0516364542", /* o */ "163645433212030516",
    /* p */ "0600|0516364543321203", /* q */ "4640|4536160503123243", /* r */ "0602|04152646",
    /* s */ "45361605143443321203", /* t */ "28233242|1636", /* u */ "0603123243|4642",
    /* v */ "062246", /* w */ "0612243246", /* x */ "0642|4602", /* y */ "0622|4610",
    /* z */ "06464202",
    /* { */ "38272615242332", /* | */ "2228", /* } */ "18272635242312", /* ~ */ "15263546"};

void ms_export_text(const char *s, const float anchor[3], float size, ms_seg_cb cb, void *ud)
{
    float unit = size * MS_EXPORT_TEXT_HEIGHT / 6.0f;   /* capitals are 6 units tall */
    float x0 = anchor[0];
    for (; *s; s++, x0 += 6.0f * unit) {
        int ch = (unsigned char)*s;
        if (ch < 32 || ch > 126) ch = '?';
        const char *g = glyphs[ch - 32];
        float prev[3];
        int have_prev = 0;
        for (; *g; ) {
            if (*g == '|') {
                have_prev = 0;
                g++;
                continue;
            }
            if (!g[1]) break;
            float p[3] = {x0 + (float)(g[0] - '0') * unit,
                          anchor[1] + (float)(g[1] - '2') * unit, anchor[2]};
            if (have_prev) cb(ud, prev, p);
            memcpy(prev, p, sizeof prev);
            have_prev = 1;
            g += 2;
        }
    }
}

void ms_export_dashes(const float a[3], const float b[3], ms_seg_cb cb, void *ud)
{
    float d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (len <= 0) return;
    long n = (long)ceilf(len / (2.0f * MS_EXPORT_DASH));
    if (n > 1000000) n = 1000000;   /* a bound for absurd lengths */
    for (long i = 0; i < n; i++) {
        float t0 = (float)(2 * i) * MS_EXPORT_DASH / len;
        float t1 = MS_MIN(1.0f, (float)(2 * i + 1) * MS_EXPORT_DASH / len);
        float p[3], q[3];
        for (int k = 0; k < 3; k++) {
            p[k] = a[k] + t0 * d[k];
            q[k] = a[k] + t1 * d[k];
        }
        cb(ud, p, q);
    }
}
