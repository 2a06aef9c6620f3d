#version 460
// Fast approximate antialiasing on the display image (after tone mapping, as FXAA expects):
// find the local luma contrast, decide whether the edge runs horizontally or vertically, walk
// along it both ways to its ends, and blend towards the neighbour across the edge by how far the
// pixel is from the nearer end, plus a sub-pixel term for isolated features. In post.chain it
// runs depth-tested over fxaa_edges.frag's mask, so only blocks with an edge pixel are shaded; the
// others keep the tone mapping's copy (what this shader would write there: the centre).
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1) uniform Params { float fxaa_threshold; float fxaa_subpixel; } params;

#include "fxaa_contrast.glsl"
float lumaAt(vec2 q) { return luma(texture(source, q).rgb); }  // between texels: filtered

void main() {
    vec2 t = 1.0 / vec2(textureSize(source, 0));
    pixel = ivec2(gl_FragCoord.xy);
    last = textureSize(source, 0) - 1;
    vec3 center = texelFetch(source, pixel, 0).rgb;
    FxaaCross around = fxaaCross(luma(center));
    float m = around.m, n = around.n, s = around.s, w = around.w, e = around.e, range = around.range;
    if (!fxaaEdge(around, params.fxaa_threshold)) {
        color = vec4(center, 1.0);
        return;
    }
    float nw = lumaNear(-1, -1), ne = lumaNear(1, -1);
    float sw = lumaNear(-1, 1), se = lumaNear(1, 1);
    // Sub-pixel aliasing: how much the centre differs from its 3x3 neighbourhood.
    float average = (2.0 * (n + s + w + e) + nw + ne + sw + se) / 12.0;
    float sub = clamp(abs(average - m) / range, 0.0, 1.0);
    sub = smoothstep(0.0, 1.0, sub);
    float subBlend = sub * sub * params.fxaa_subpixel;
    // Edge direction.
    float horizontal = abs(nw + sw - 2.0 * w) + 2.0 * abs(n + s - 2.0 * m) + abs(ne + se - 2.0 * e);
    float vertical = abs(nw + ne - 2.0 * n) + 2.0 * abs(w + e - 2.0 * m) + abs(sw + se - 2.0 * s);
    bool isHorizontal = horizontal >= vertical;
    float l1 = isHorizontal ? n : w, l2 = isHorizontal ? s : e;
    float g1 = abs(l1 - m), g2 = abs(l2 - m);
    bool towardsFirst = g1 >= g2;
    float stepLength = isHorizontal ? t.y : t.x;
    float neighbour = towardsFirst ? l1 : l2;
    float gradient = 0.25 * max(g1, g2);
    if (towardsFirst) stepLength = -stepLength;
    vec2 edge = uv;
    if (isHorizontal) edge.y += 0.5 * stepLength; else edge.x += 0.5 * stepLength;
    vec2 along = isHorizontal ? vec2(t.x, 0) : vec2(0, t.y);
    float edgeLuma = 0.5 * (m + neighbour);
    // Walk both ways until the luma along the edge changes by more than the gradient.
    vec2 p1 = edge - along, p2 = edge + along;
    float d1 = lumaAt(p1) - edgeLuma, d2 = lumaAt(p2) - edgeLuma;
    bool done1 = abs(d1) >= gradient, done2 = abs(d2) >= gradient;
    // Four growing steps: on a CPU rasteriser every step runs for every pixel (no early exit),
    // so the walk is short; edges longer than ~9 texels get a partial blend.
    const float steps[4] = float[](1.5, 2.0, 2.0, 4.0);
    for (int i = 0; i < 4 && !(done1 && done2); ++i) {
        if (!done1) { p1 -= along * steps[i]; d1 = lumaAt(p1) - edgeLuma; done1 = abs(d1) >= gradient; }
        if (!done2) { p2 += along * steps[i]; d2 = lumaAt(p2) - edgeLuma; done2 = abs(d2) >= gradient; }
    }
    float dist1 = isHorizontal ? uv.x - p1.x : uv.y - p1.y;
    float dist2 = isHorizontal ? p2.x - uv.x : p2.y - uv.y;
    bool nearFirst = dist1 < dist2;
    float nearest = min(dist1, dist2);
    float length = dist1 + dist2;
    // Blend only when the centre lies on the side of the edge the nearer end moves away from.
    bool centreSmaller = m - edgeLuma < 0.0;
    bool goodSpan = ((nearFirst ? d1 : d2) < 0.0) != centreSmaller;
    float edgeBlend = goodSpan ? 0.5 - nearest / length : 0.0;
    float blend = max(edgeBlend, subBlend);
    vec2 q = uv;
    if (isHorizontal) q.y += blend * stepLength; else q.x += blend * stepLength;
    color = vec4(texture(source, q).rgb, 1.0);
}
