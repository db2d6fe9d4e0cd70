/* shaders.c: the GLSL 3.30 core programs of the renderer, in the spirit of VMD's GLSL mode.
 * Spheres, cylinders and cones are ray-cast per pixel inside a screen rectangle that bounds
 * their exact projection (no tessellation: exact silhouettes, exact depth written to
 * gl_FragDepth, cut open at the near plane). Every lit surface gets per-pixel Blinn-Phong
 * with VMD's directional lights and the item's material, the material's outline, depth
 * cueing toward the background and, for translucent surfaces, weighted blended
 * order-independent transparency (McGuire and Bavoil 2013). Lines, points and text strokes
 * are flat-coloured screen-space quads a given number of pixels wide, as VMD draws them. */
#include "config.h"
#include "gl/glrender.h"

/* Uniforms and helpers every surface fragment shader shares. Eye space: the eye at the
 * origin looking down -z; u_ray maps normalised device coordinates onto eye rays. */
static const char fs_common[] =
    "#version 330 core\n"
    "uniform mat4 u_proj;\n"
    "uniform vec2 u_viewport;\n"
    "uniform vec3 u_ray;        /* tan or half size in x and y; z = 1: orthographic */\n"
    "uniform vec2 u_nearfar;\n"
    "uniform int u_nlights;\n"
    "uniform vec3 u_light_dir[4];\n"
    "uniform vec3 u_light_col[4];\n"
    "uniform vec4 u_mat;        /* ambient, diffuse, specular, shininess exponent */\n"
    "uniform vec4 u_mat2;       /* opacity, outline, outline width, transmode */\n"
    "uniform int u_lit;\n"
    "uniform int u_fog;         /* 0 off, 1 linear, 2 exp, 3 exp2 */\n"
    "uniform vec3 u_fogp;       /* start, end, density */\n"
    "uniform vec3 u_bg_top, u_bg_bot;\n"
    "uniform int u_pass;        /* 0 opaque, 1 translucent */\n"
    "layout(location = 0) out vec4 o_color;\n"
    "layout(location = 1) out vec4 o_weight;\n"
    "void eye_ray(out vec3 o, out vec3 d) {\n"
    "    vec2 ndc = gl_FragCoord.xy / u_viewport * 2.0 - 1.0;\n"
    "    if (u_ray.z > 0.5) { o = vec3(ndc * u_ray.xy, 0.0); d = vec3(0.0, 0.0, -1.0); }\n"
    "    else { o = vec3(0.0); d = normalize(vec3(ndc * u_ray.xy, -1.0)); }\n"
    "}\n"
    "float depth_of(vec3 p) { vec4 c = u_proj * vec4(p, 1.0); return 0.5 * c.z / c.w + 0.5; }\n"
    "bool clipped(vec3 p) { return -p.z < u_nearfar.x || -p.z > u_nearfar.y; }\n"
    "vec3 background() { return mix(u_bg_bot, u_bg_top, gl_FragCoord.y / u_viewport.y); }\n"
    "vec3 lighting(vec3 col, vec3 n, vec3 v) {\n"
    "    vec3 dif = vec3(0.0), spe = vec3(0.0);\n"
    "    for (int i = 0; i < u_nlights; i++) {\n"
    "        float nl = dot(n, u_light_dir[i]);\n"
    "        if (nl <= 0.0) continue;\n"
    "        dif += nl * u_light_col[i];\n"
    "        float nh = max(dot(n, normalize(u_light_dir[i] + v)), 0.0);\n"
    "        spe += pow(nh, u_mat.w) * u_light_col[i];\n"
    "    }\n"
    "    return col * (u_mat.x + u_mat.y * dif) + u_mat.z * spe;\n"
    "}\n"
    "float fog(float dist) {\n"
    "    float f = 1.0;\n"
    "    if (u_fog == 1) f = (u_fogp.y - dist) / (u_fogp.y - u_fogp.x);\n"
    "    else if (u_fog == 2) f = exp(-u_fogp.z * dist);\n"
    "    else if (u_fog == 3) f = exp(-(u_fogp.z * dist) * (u_fogp.z * dist));\n"
    "    return clamp(f, 0.0, 1.0);\n"
    "}\n"
    "/* Shade a surface point p (eye space) with normal n seen along v, then write it to the\n"
    "   opaque or the translucent targets. */\n"
    "void surface(vec3 col, float alpha, vec3 p, vec3 n, vec3 v) {\n"
    "    float a = alpha * u_mat2.x;\n"
    "    if ((u_pass == 0) != (a >= 1.0)) discard;\n"
    "    if (dot(n, v) < 0.0) n = -n;\n"
    "    vec3 c = col;\n"
    "    if (u_lit != 0) {\n"
    "        c = lighting(col, n, v);\n"
    "        float nv = clamp(dot(n, v), 0.0, 1.0);\n"
    "        if (u_mat2.y > 0.0) {\n"
    "            float e = 1.0 - pow(1.0 - nv * nv, (1.0 - u_mat2.z) * 32.0);\n"
    "            c *= clamp(1.0 - u_mat2.y + e * u_mat2.y, 0.0, 1.0);\n"
    "        }\n"
    "        if (u_mat2.w > 0.0 && a < 1.0) {\n"
    "            float q = 1.0 + cos(3.14159265 * (1.0 - a) * nv);\n"
    "            a = q * q * 0.25;\n"
    "        }\n"
    "    }\n"
    "    c = mix(background(), c, fog(-p.z));\n"
    "    if (u_pass == 0) { o_color = vec4(c, 1.0); o_weight = vec4(0.0); return; }\n"
    "    float d = -p.z;\n"
    "    float w = a * clamp(10.0 / (1e-5 + pow(d / 5.0, 2.0) + pow(d / 200.0, 6.0)), 1e-2, 3e3);\n"
    "    o_color = vec4(c * a * w, a);\n"
    "    o_weight = vec4(a * w);\n"
    "}\n"
    "/* Flat colour (lines, points, text): fog only. */\n"
    "void flat_color(vec4 col, vec3 p) {\n"
    "    float a = col.a * u_mat2.x;\n"
    "    if ((u_pass == 0) != (a >= 1.0)) discard;\n"
    "    vec3 c = mix(background(), col.rgb, fog(-p.z));\n"
    "    if (u_pass == 0) { o_color = vec4(c, 1.0); o_weight = vec4(0.0); return; }\n"
    "    o_color = vec4(c * a, a);\n"
    "    o_weight = vec4(a);\n"
    "}\n";

/* Screen rectangle (normalised device coordinates) bounding one or two balls exactly: under
 * perspective each ball's x and y bounds are the slopes of the planes through the eye that
 * touch it. A ball crossing the eye plane gets the whole screen; a primitive whose balls
 * both lie nearer than the near plane, or both beyond the far plane, an empty rectangle. */
static const char vs_bounds[] =
    "#version 330 core\n"
    "uniform mat4 u_mv;\n"
    "uniform float u_rscale;\n"
    "uniform vec3 u_ray;\n"
    "uniform vec2 u_nearfar;\n"
    "uniform vec2 u_viewport;\n"
    "vec2 slopes(float c, float dd, float r) {\n"
    "    float k = dd * dd - r * r, s = r * sqrt(max(c * c + k, 0.0));\n"
    "    return vec2(c * dd - s, c * dd + s) / k;\n"
    "}\n"
    "int ball_side(vec3 c, float r) {\n"
    "    return -c.z + r < u_nearfar.x ? -1 : -c.z - r > u_nearfar.y ? 1 : 0;\n"
    "}\n"
    "vec4 sphere_rect(vec3 c, float r) {\n"
    "    float dd = -c.z;\n"
    "    if (u_ray.z > 0.5) return vec4((c.xy - r) / u_ray.xy, (c.xy + r) / u_ray.xy);\n"
    "    if (dd <= r * 1.0001) return vec4(-1.0, -1.0, 1.0, 1.0);\n"
    "    vec2 sx = slopes(c.x, dd, r) / u_ray.x, sy = slopes(c.y, dd, r) / u_ray.y;\n"
    "    return vec4(sx.x, sy.x, sx.y, sy.y);\n"
    "}\n"
    "/* The corner gl_VertexID (0..3, a triangle strip) of the balls' rectangles' union, widened\n"
    "   by 0.05 pixel so that rasterizers snapping corners to a subpixel grid still sample\n"
    "   every pixel centre inside (the occlusion culling counts on it). */\n"
    "vec4 corner(vec3 ca, float ra, vec3 cb, float rb) {\n"
    "    int side = ball_side(ca, ra);\n"
    "    if (side != 0 && side == ball_side(cb, rb)) return vec4(2.0, 2.0, 2.0, 1.0);\n"
    "    vec4 a = sphere_rect(ca, ra), b = sphere_rect(cb, rb);\n"
    "    vec4 r = vec4(min(a.xy, b.xy), max(a.zw, b.zw));\n"
    "    vec2 m = 0.1 / u_viewport;\n"
    "    r = clamp(r + vec4(-m, m), -1.0, 1.0);\n"
    "    vec2 p = vec2((gl_VertexID & 1) != 0 ? r.z : r.x, (gl_VertexID & 2) != 0 ? r.w : r.y);\n"
    "    return vec4(p, 0.0, 1.0);\n"
    "}\n";

static const char vs_sphere[] =
    "layout(location = 0) in vec3 a_center;\n"
    "layout(location = 1) in float a_radius;\n"
    "layout(location = 2) in vec4 a_color;\n"
    "flat out vec3 v_center;\n"
    "flat out float v_radius;\n"
    "flat out vec4 v_color;\n"
    "void main() {\n"
    "    v_center = (u_mv * vec4(a_center, 1.0)).xyz;\n"
    "    v_radius = a_radius * u_rscale;\n"
    "    v_color = a_color;\n"
    "    gl_Position = corner(v_center, v_radius, v_center, v_radius);\n"
    "}\n";

/* The ray is first moved to the point nearest the centre, so that what follows works with
 * lengths of the sphere's size (a tiny sphere far from the eye keeps its precision). */
static const char fs_sphere[] =
    "flat in vec3 v_center;\n"
    "flat in float v_radius;\n"
    "flat in vec4 v_color;\n"
    "void main() {\n"
    "    vec3 o, d;\n"
    "    eye_ray(o, d);\n"
    "    float t0 = dot(v_center - o, d);\n"
    "    vec3 m = o + t0 * d - v_center;\n"
    "    float h = v_radius * v_radius - dot(m, m);\n"
    "    if (h < 0.0) discard;\n"
    "    h = sqrt(h);\n"
    "    vec3 p = o + (t0 - h) * d;\n"
    "    if (clipped(p)) {\n"
    "        p = o + (t0 + h) * d;\n"
    "        if (clipped(p)) discard;\n"
    "    }\n"
    "    gl_FragDepth = depth_of(p);\n"
    "    surface(v_color.rgb, v_color.a, p, (p - v_center) / v_radius, -d);\n"
    "}\n";

/* Cylinders and cones: a truncated cone from a_base (radius a_rbase) to a_apex (a_rapex),
 * with the end discs named in a_caps (1 base, 2 apex) closed; the half nearer the apex takes
 * a_color2 (merged half-bond pairs; otherwise the same colour). */
static const char vs_cone[] =
    "layout(location = 0) in vec3 a_base;\n"
    "layout(location = 1) in vec3 a_apex;\n"
    "layout(location = 2) in float a_rbase;\n"
    "layout(location = 3) in float a_rapex;\n"
    "layout(location = 4) in vec4 a_color;\n"
    "layout(location = 5) in float a_caps;\n"
    "layout(location = 6) in vec4 a_color2;\n"
    "flat out vec3 v_base, v_apex;\n"
    "flat out vec2 v_radii;\n"
    "flat out vec4 v_color, v_color2;\n"
    "flat out int v_caps;\n"
    "void main() {\n"
    "    v_base = (u_mv * vec4(a_base, 1.0)).xyz;\n"
    "    v_apex = (u_mv * vec4(a_apex, 1.0)).xyz;\n"
    "    v_radii = vec2(a_rbase, a_rapex) * u_rscale;\n"
    "    v_color = a_color;\n"
    "    v_color2 = a_color2;\n"
    "    v_caps = int(a_caps + 0.5);\n"
    "    gl_Position = corner(v_base, v_radii.x, v_apex, v_radii.y);\n"
    "}\n";

static const char fs_cone[] =
    "flat in vec3 v_base, v_apex;\n"
    "flat in vec2 v_radii;\n"
    "flat in vec4 v_color, v_color2;\n"
    "flat in int v_caps;\n"
    "float best_t; vec3 best_n;\n"
    "vec3 o1, d1;\n"
    "void consider(float t, vec3 n) {\n"
    "    if (t < best_t && !clipped(o1 + t * d1)) { best_t = t; best_n = n; }\n"
    "}\n"
    "void cap(vec3 c, vec3 n, float r) {\n"
    "    float dn = dot(d1, n);\n"
    "    if (abs(dn) < 1e-12) return;\n"
    "    float t = dot(c - o1, n) / dn;\n"
    "    vec3 q = o1 + t * d1 - c;\n"
    "    if (dot(q, q) <= r * r) consider(t, n);\n"
    "}\n"
    "void main() {\n"
    "    vec3 o, d;\n"
    "    eye_ray(o, d);\n"
    "    float t0 = dot(0.5 * (v_base + v_apex) - o, d);\n"
    "    o1 = o + t0 * d; d1 = d;\n"
    "    vec3 ax = v_apex - v_base;\n"
    "    float len = length(ax);\n"
    "    if (len <= 0.0) discard;\n"
    "    vec3 u = ax / len;\n"
    "    float k = (v_radii.y - v_radii.x) / len;\n"
    "    vec3 w = o1 - v_base;\n"
    "    float ws = dot(w, u), ds = dot(d, u);\n"
    "    vec3 wp = w - ws * u, dp = d - ds * u;\n"
    "    float r0 = v_radii.x + k * ws, r1 = k * ds;\n"
    "    float qa = dot(dp, dp) - r1 * r1, qb = dot(wp, dp) - r0 * r1;\n"
    "    float qc = dot(wp, wp) - r0 * r0;\n"
    "    best_t = 1e30;\n"
    "    float disc = qb * qb - qa * qc;\n"
    "    if (disc >= 0.0 && abs(qa) > 1e-20) {\n"
    "        float sq = sqrt(disc);\n"
    "        for (int i = 0; i < 2; i++) {\n"
    "            float t = (-qb + (i == 0 ? -sq : sq)) / qa;\n"
    "            float s = ws + t * ds;\n"
    "            if (s < 0.0 || s > len || r0 + r1 * t < 0.0) continue;\n"
    "            vec3 rv = wp + t * dp;\n"
    "            consider(t, normalize(normalize(rv) - k * u));\n"
    "        }\n"
    "    }\n"
    "    if ((v_caps & 1) != 0) cap(v_base, -u, v_radii.x);\n"
    "    if ((v_caps & 2) != 0) cap(v_apex, u, v_radii.y);\n"
    "    if (best_t > 1e29) discard;\n"
    "    vec3 p = o1 + best_t * d;\n"
    "    gl_FragDepth = depth_of(p);\n"
    "    vec4 col = ws + best_t * ds < 0.5 * len ? v_color : v_color2;\n"
    "    surface(col.rgb, col.a, p, best_n, -d);\n"
    "}\n";

/* Triangle meshes: normals arrive as the signed bytes of the display list. */
static const char vs_mesh[] =
    "#version 330 core\n"
    "uniform mat4 u_mv;\n"
    "uniform mat4 u_proj;\n"
    "layout(location = 0) in vec3 a_pos;\n"
    "layout(location = 1) in vec3 a_normal;\n"
    "layout(location = 2) in vec4 a_color;\n"
    "out vec3 v_pos, v_normal;\n"
    "out vec4 v_color;\n"
    "void main() {\n"
    "    v_pos = (u_mv * vec4(a_pos, 1.0)).xyz;\n"
    "    v_normal = mat3(u_mv) * ((2.0 * a_normal + 1.0) / 255.0);\n"
    "    v_color = a_color;\n"
    "    gl_Position = u_proj * vec4(v_pos, 1.0);\n"
    "}\n";

static const char fs_mesh[] =
    "in vec3 v_pos, v_normal;\n"
    "in vec4 v_color;\n"
    "void main() {\n"
    "    vec3 v = u_ray.z > 0.5 ? vec3(0.0, 0.0, 1.0) : -normalize(v_pos);\n"
    "    surface(v_color.rgb, v_color.a, v_pos, normalize(v_normal), v);\n"
    "}\n";

/* Lines (and points: u_square extends a zero-length line into a square) a_width pixels
 * wide; segments are cut at the near plane first. Dashes are VMD's: 0.02 world units on,
 * 0.02 off (the exporters' length). */
static const char vs_line[] =
    "#version 330 core\n"
    "uniform mat4 u_mv;\n"
    "uniform mat4 u_proj;\n"
    "uniform vec2 u_viewport;\n"
    "uniform vec2 u_nearfar;\n"
    "uniform int u_square;\n"
    "layout(location = 0) in vec3 a_a;\n"
    "layout(location = 1) in vec3 a_b;\n"
    "layout(location = 2) in float a_width;\n"
    "layout(location = 3) in vec4 a_color;\n"
    "layout(location = 4) in float a_style;\n"
    "out vec3 v_pos;\n"
    "out float v_s;\n"
    "flat out vec4 v_color;\n"
    "flat out int v_dashed;\n"
    "void main() {\n"
    "    vec3 pa = (u_mv * vec4(a_a, 1.0)).xyz, pb = (u_mv * vec4(a_b, 1.0)).xyz;\n"
    "    float sa = 0.0, sb = length(pb - pa), zn = -u_nearfar.x;\n"
    "    v_color = a_color;\n"
    "    v_dashed = int(a_style + 0.5);\n"
    "    if (pa.z > zn && pb.z > zn) { gl_Position = vec4(2.0, 2.0, 2.0, 1.0); return; }\n"
    "    if (pa.z > zn) {\n"
    "        float f = (zn - pb.z) / (pa.z - pb.z);\n"
    "        pa = mix(pb, pa, f);\n"
    "        sa = sb * (1.0 - f);\n"
    "    }\n"
    "    if (pb.z > zn) {\n"
    "        float f = (zn - pa.z) / (pb.z - pa.z);\n"
    "        pb = mix(pa, pb, f);\n"
    "        sb = sb * f;\n"
    "    }\n"
    "    vec4 ca = u_proj * vec4(pa, 1.0), cb = u_proj * vec4(pb, 1.0);\n"
    "    vec2 half_vp = 0.5 * u_viewport;\n"
    "    vec2 dir = (cb.xy / cb.w - ca.xy / ca.w) * half_vp;\n"
    "    dir = length(dir) > 1e-6 ? normalize(dir) : vec2(1.0, 0.0);\n"
    "    vec2 side = vec2(-dir.y, dir.x);\n"
    "    bool at_b = (gl_VertexID & 1) != 0;\n"
    "    vec2 off = side * ((gl_VertexID & 2) != 0 ? 0.5 : -0.5) * a_width;\n"
    "    if (u_square != 0) off += dir * (at_b ? 0.5 : -0.5) * a_width;\n"
    "    vec4 c = at_b ? cb : ca;\n"
    "    c.xy += off / half_vp * c.w;\n"
    "    v_pos = at_b ? pb : pa;\n"
    "    v_s = at_b ? sb : sa;\n"
    "    gl_Position = c;\n"
    "}\n";

static const char fs_line[] =
    "in vec3 v_pos;\n"
    "in float v_s;\n"
    "flat in vec4 v_color;\n"
    "flat in int v_dashed;\n"
    "void main() {\n"
    "    if (v_dashed != 0 && mod(v_s, 0.04) > 0.02) discard;\n"
    "    flat_color(v_color, v_pos);\n"
    "}\n";

/* A triangle covering the screen, for the background gradient and the composite pass. */
static const char vs_screen[] =
    "#version 330 core\n"
    "void main() {\n"
    "    vec2 p = vec2((gl_VertexID & 1) != 0 ? 3.0 : -1.0, (gl_VertexID & 2) != 0 ? 3.0 : -1.0);\n"
    "    gl_Position = vec4(p, 1.0, 1.0);\n"
    "}\n";

static const char fs_gradient[] =
    "#version 330 core\n"
    "uniform vec2 u_viewport;\n"
    "uniform vec3 u_bg_top, u_bg_bot;\n"
    "layout(location = 0) out vec4 o_color;\n"
    "void main() {\n"
    "    o_color = vec4(mix(u_bg_bot, u_bg_top, gl_FragCoord.y / u_viewport.y), 1.0);\n"
    "}\n";

/* Weighted blended OIT resolve: the weighted mean colour of the translucent layers, laid
 * over the opaque image with coverage 1 - (product of their transparencies). */
static const char fs_composite[] =
    "#version 330 core\n"
    "uniform sampler2D u_accum;\n"
    "uniform sampler2D u_wsum;\n"
    "layout(location = 0) out vec4 o_color;\n"
    "void main() {\n"
    "    ivec2 px = ivec2(gl_FragCoord.xy);\n"
    "    vec4 acc = texelFetch(u_accum, px, 0);\n"
    "    if (acc.a >= 1.0) discard;\n"
    "    float ws = texelFetch(u_wsum, px, 0).r;\n"
    "    o_color = vec4(acc.rgb / max(ws, 1e-5), 1.0 - acc.a);\n"
    "}\n";

const ms_glr_source ms_glr_sources[MS_GLR_NPROGS] = {
    [MS_GLR_SPHERE] = {"sphere", {vs_bounds, vs_sphere}, {fs_common, fs_sphere}},
    [MS_GLR_CONE] = {"cone", {vs_bounds, vs_cone}, {fs_common, fs_cone}},
    [MS_GLR_MESH] = {"mesh", {vs_mesh, ""}, {fs_common, fs_mesh}},
    [MS_GLR_LINE] = {"line", {vs_line, ""}, {fs_common, fs_line}},
    [MS_GLR_GRADIENT] = {"gradient", {vs_screen, ""}, {fs_gradient, ""}},
    [MS_GLR_COMPOSITE] = {"composite", {vs_screen, ""}, {fs_composite, ""}},
};
