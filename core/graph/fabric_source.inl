// The fabric nodes' functions, written once in the common subset of GLSL 4.50 and C++20 with GLM
// (float literals with an `f` suffix, which GLSL accepts since 1.30; no swizzles beyond .x/.y/.z;
// out parameters through VELVET_OUT). core/graph/fabric_glsl.cpp turns this text into the GLSL
// helper the graph compiler emits; core/graph/fabric.cpp compiles the same tokens as the C++ twin.
// So the GPU and the CPU run the same statements; only the float maths libraries differ.
//
// Not a header: included only by those two files, each of which defines VELVET_FABRIC_SOURCE.
// Preprocessor lines are not allowed inside (the GLSL side is a stringified macro argument).
//
// Conventions. UV (u, v); warp ends run along v and are counted along u (warp density = ends per
// UV unit), weft picks run along u and are counted along v. A "cell" is one crossing of end i and
// pick j. Heights are normalised to [0, 1] (1: the crown of a yarn at the middle of a float); the
// physical height is crossingHeight * height in units of the mean thread spacing, and normals are
// that height's gradient in UV, in tangent space (+Z out of the surface, +U = tangent, +V =
// bitangent, OpenGL convention).
VELVET_FABRIC_SOURCE(

// a - n floor(a / n) for whole numbers a and n >= 1, safe against an inexact GPU division: (a + 0.5)
// / n is at least 0.5 / n away from a whole number, so its floor is exact.
float velvetFabricMod(float a, float n) {
    return a - n * floor((a + 0.5f) / n);
}

// The cross-section of a yarn: (1 - x^2)^(r / 2) for x in [-1, 1] across it, roundness r (0: flat
// tape, 1: elliptical, 2: parabolic), and its derivative d/dx. 1 - x^2 is held above 0.04 so the
// slope at the edge stays finite (a yarn edge is steep but not vertical).
float velvetYarnProfile(float x, float r, VELVET_OUT(float) slope) {
    float q = 1.0f - x * x;
    float qc = max(q, 0.04f);
    float p = pow(qc, 0.5f * r);
    slope = q > 0.04f ? -r * x * p / qc : 0.0f;
    return p;
}

// The rise of a yarn along its length t in [0, 1] of one cell: sin(pi t) on a side where the
// yarn changes between over and under at the cell's edge, 1 (flat) on a side where the float goes
// on into the next cell, with the derivative d/dt. Continuous in value and slope at t = 0.5.
float velvetYarnArc(float t, float contLo, float contHi, VELVET_OUT(float) slope) {
    float cont = t < 0.5f ? contLo : contHi;
    slope = cont > 0.5f ? 0.0f : 3.14159265f * cos(3.14159265f * t);
    return cont > 0.5f ? 1.0f : sin(3.14159265f * t);
}

// 1 where warp end i passes over weft pick j, 0 where it passes under. The weave diagram
// (draft) of each pattern, in the textile-design definitions (Watson, "Textile Design and
// Colour", ch. 1-3; Grosicki 1975):
//   0 plain:       over one, under one, alternating on every end (a checkerboard).
//   1 twill n/m:   each end over `over` picks, under `under`, the start moving `step` picks per end
//                  (step 1: the classic 45-degree twill line when densities are equal).
//   2 satin:       an N-harness satin (N = `harness`): each end floats over N - 1 picks and
//                  interlaces once; the interlacing moves by the counter `step` per end.
//   3 basket:      plain weave of `group` x `group` ends and picks woven as one.
//   4 herringbone: the twill, its direction reversed every `group` ends, shifted by half a repeat
//                  at each reversal (a broken twill, so the stripes meet at a break, not a point).
float velvetWeaveWarpUp(float i, float j, float pattern, float over, float under, float harness,
                        float step, float group) {
    int p = int(pattern + 0.5f);
    float g = max(floor(group + 0.5f), 1.0f);
    if (p == 0)
        return 1.0f - velvetFabricMod(i + j, 2.0f);
    if (p == 3)
        return 1.0f - velvetFabricMod(floor((i + 0.5f) / g) + floor((j + 0.5f) / g), 2.0f);
    float n = max(floor(over + 0.5f), 1.0f);
    float m = max(floor(under + 0.5f), 1.0f);
    float s = floor(step + 0.5f);
    if (p == 2) {
        n = max(floor(harness + 0.5f), 3.0f) - 1.0f;
        m = 1.0f;
    }
    float repeat = n + m;
    float phase = j + s * i;
    if (p == 4 && velvetFabricMod(floor((i + 0.5f) / g), 2.0f) > 0.5f)
        phase = j - s * i + floor(0.5f * repeat);
    return velvetFabricMod(phase, repeat) < n - 0.5f ? 1.0f : 0.0f;
}

// The means of the Weave's outputs over one repeat of the pattern, what a pixel covering many
// threads should show (the filtering below fades to them). A model of the node's own statements,
// not an exact integral: with w the yarn width, a cell is w^2 where warp and weft cross (the yarn
// on top seen: warp with the face's warp share s of the crossings), w (1 - w) twice where one yarn
// lies alone, and (1 - w)^2 of gap. A yarn's mean height is its cross-section's mean P(r),
// (1 - x^2)^(r / 2) over [-1, 1] (fitted as exp(-0.242 r^0.66), within 0.01 for r in [0, 2]),
// times its mean rise along the crossings, 1 - 0.165 per interlacing per cell (a sine arch at an
// interlacing, flat along a float), 0.55 where a yarn lies alone (as often under as over).
// test_core_fabric measures each against the average of the unfiltered pattern.
struct VelvetWeaveMean {
    vec3 color;
    float height;
    float sheen;
    float warp;
};

VelvetWeaveMean velvetWeaveMean(float pattern, float over, float under, float harness,
                                float group, float width, float roundness, vec3 warpColor,
                                vec3 weftColor) {
    int p = int(pattern + 0.5f);
    float n = max(floor(over + 0.5f), 1.0f);
    float m = max(floor(under + 0.5f), 1.0f);
    float harnessN = max(floor(harness + 0.5f), 3.0f);
    float g = max(floor(group + 0.5f), 1.0f);
    float share = n / (n + m);
    float interlacings = 2.0f / (n + m);
    if (p == 0) {
        share = 0.5f;
        interlacings = 1.0f;
    } else if (p == 3) {
        share = 0.5f;
        interlacings = 1.0f / g;
    } else if (p == 2) {
        share = (harnessN - 1.0f) / harnessN;
        interlacings = 2.0f / harnessN;
    }
    float w = clamp(width, 0.05f, 1.0f);
    float crossing = w * w;
    float alone = w * (1.0f - w);
    float gap = (1.0f - w) * (1.0f - w);
    float warpArea = alone + crossing * share;
    float weftArea = alone + crossing * (1.0f - share);
    float profile = exp(-0.242f * pow(max(roundness, 0.0f), 0.66f));
    VelvetWeaveMean o;
    o.height = profile * (crossing * (1.0f - 0.165f * interlacings) + 2.0f * alone * 0.55f);
    float warpHeight = o.height * warpArea / (warpArea + weftArea);
    float weftHeight = o.height - warpHeight;
    o.color = warpColor * (0.7f * warpArea + 0.3f * warpHeight) +
              weftColor * (0.7f * weftArea + 0.3f * weftHeight) +
              0.175f * gap * (warpColor + weftColor);
    o.sheen = profile * (crossing + 2.0f * alone * 0.7f);
    o.warp = warpArea;
    return o;
}

// What the Weave node outputs at one point.
struct VelvetWeave {
    vec3 color;     // the visible yarn's colour, darkened towards its hollows
    float height;   // [0, 1]
    vec3 normal;    // tangent space
    float roughness;
    float sheen;    // [0, 1]: the crowns of the floats on top
    vec2 direction; // tangent-space direction of the visible yarn (warp (0, 1), weft (1, 0))
    float thread;   // a value in [0, 1) per thread: fract(index / golden ratio), weft offset by 0.5
    float warp;     // 1 where a warp end is seen, 0 where a weft pick or a gap is
    float occlusion;
};

VelvetWeave velvetWeave(vec2 uv, float pattern, float over, float under, float harness, float step,
                        float group, vec2 density, float width, float roundness, vec3 warpColor,
                        vec3 weftColor, float crossingHeight, float roughness, vec2 footprint) {
    vec2 d = max(density, vec2(1e-3f));
    float w = clamp(width, 0.05f, 1.0f);
    float X = uv.x * d.x;
    float Y = uv.y * d.y;
    float i = floor(X);
    float j = floor(Y);
    float fu = X - i;
    float fv = Y - j;
    float up = velvetWeaveWarpUp(i, j, pattern, over, under, harness, step, group);
    float upLo = velvetWeaveWarpUp(i, j - 1.0f, pattern, over, under, harness, step, group);
    float upHi = velvetWeaveWarpUp(i, j + 1.0f, pattern, over, under, harness, step, group);
    float upL = velvetWeaveWarpUp(i - 1.0f, j, pattern, over, under, harness, step, group);
    float upR = velvetWeaveWarpUp(i + 1.0f, j, pattern, over, under, harness, step, group);

    // The warp end: across it x = (fu - 1/2) / (w / 2), along it t = fv; up: 1/2 + arc / 2,
    // under: 1/2 - arc / 2, so the two meet at 1/2 where an end changes sides at a cell edge.
    float sigma = 2.0f * up - 1.0f;
    float xw = (fu - 0.5f) * 2.0f / w;
    float pwSlope;
    float pw = velvetYarnProfile(xw, roundness, pwSlope);
    float awSlope;
    float aw = velvetYarnArc(fv, upLo == up ? 1.0f : 0.0f, upHi == up ? 1.0f : 0.0f, awSlope);
    float lw = 0.5f + 0.5f * sigma * aw;
    float hw = abs(xw) < 1.0f ? lw * pw : -1.0f;
    // The weft pick: across it x = (fv - 1/2) / (w / 2), along it t = fu, on the other side.
    float xf = (fv - 0.5f) * 2.0f / w;
    float pfSlope;
    float pf = velvetYarnProfile(xf, roundness, pfSlope);
    float afSlope;
    float af = velvetYarnArc(fu, upL == up ? 1.0f : 0.0f, upR == up ? 1.0f : 0.0f, afSlope);
    float lf = 0.5f - 0.5f * sigma * af;
    float hf = abs(xf) < 1.0f ? lf * pf : -1.0f;

    VelvetWeave o;
    // d(height)/d(u, v) of the yarn seen, then scaled to UV units of physical height.
    vec2 grad = vec2(0.0f);
    if (hw < 0.0f && hf < 0.0f) {
        // A gap between yarns: the other side of the cloth, in shadow (half the yarns' mean).
        o.height = 0.0f;
        o.color = 0.25f * (warpColor + weftColor);
        o.sheen = 0.0f;
        o.direction = vec2(0.0f, 1.0f);
        o.thread = 0.0f;
        o.warp = 0.0f;
    } else if (hw >= hf) {
        o.height = hw;
        grad = vec2(lw * pwSlope * 2.0f * d.x / w, pw * 0.5f * sigma * awSlope * d.y);
        o.color = warpColor;
        o.sheen = pw * (up > 0.5f ? 1.0f : 0.4f);
        o.direction = vec2(0.0f, 1.0f);
        o.thread = fract(i * 0.61803398875f);
        o.warp = 1.0f;
    } else {
        o.height = hf;
        grad = vec2(-pf * 0.5f * sigma * afSlope * d.x, lf * pfSlope * 2.0f * d.y / w);
        o.color = weftColor;
        o.sheen = pf * (up > 0.5f ? 0.4f : 1.0f);
        o.direction = vec2(1.0f, 0.0f);
        o.thread = fract(j * 0.61803398875f + 0.5f);
        o.warp = 0.0f;
    }
    // Light scattered between a yarn's fibres leaves darker from its hollows (colour) and less of
    // the environment reaches them (occlusion).
    o.color = o.color * (0.7f + 0.3f * o.height);

    // Filtering by the pixel's footprint (Ebert et al., "Texturing and Modeling", 3rd ed., ch. 2,
    // "Antialiasing procedural textures": fade a pattern to its average where it is finer than a
    // pixel; Quilez, "filterable procedurals"): where a pixel spans more than a quarter of a
    // thread the yarns' edges alias into moire, so every output fades to the pattern's mean,
    // reached where it spans three quarters. footprint: the UV extent of a pixel along u and v
    // (fwidth(uv) on the GPU; (0, 0): unfiltered, as the path tracer, which averages many samples
    // a pixel, wants). The thread id is an identity, not a quantity, and is left as it is. What
    // one flat normal cannot stand for: a pixel over many bumps reflects as their distribution
    // of normals does, brighter towards grazing angles (against the path tracer on a 32 x 32
    // sphere, test_app_reference_table, cotton's mean dE2000 under the HDRI went from 5.9 to 7.0,
    // darker at the rim); the roughness below takes the specular part, a diffuse counterpart in
    // the lighting is left to do. Keeping the normal unfiltered instead shows moire rings on
    // silk and satin in a 256-pixel thumbnail.
    float cells = max(footprint.x * d.x, footprint.y * d.y);
    float fade = smoothstep(0.25f, 0.75f, cells);
    VelvetWeaveMean mean =
        velvetWeaveMean(pattern, over, under, harness, group, width, roundness, warpColor,
                        weftColor);
    o.color = mix(o.color, mean.color, fade);
    o.height = mix(o.height, mean.height, fade);
    o.sheen = mix(o.sheen, mean.sheen, fade);
    o.warp = mix(o.warp, mean.warp, fade);
    if (fade > 0.5f)
        o.direction = mean.warp >= 0.5f * (1.0f - (1.0f - w) * (1.0f - w)) ? vec2(0.0f, 1.0f)
                                                                          : vec2(1.0f, 0.0f);
    // The height fades to a constant, so its gradient (the normal's tilt) fades to 0.
    grad = grad * ((1.0f - fade) * crossingHeight * 2.0f / (d.x + d.y));
    o.normal = normalize(vec3(-grad.x, -grad.y, 1.0f));
    o.occlusion = 0.45f + 0.55f * o.height;
    o.roughness = clamp(roughness + 0.15f * (1.0f - o.height), 0.0f, 1.0f);
    // The relief that fades out of the normal goes into the roughness, as when mipmapping normal
    // maps (Toksvig 2005, "Mipmapping Normal Maps"; Olano & Baker 2010, LEAN mapping): GGX's
    // alpha^2 (alpha = roughness^2) grows by the variance of the slopes the pixel averages,
    // modelled as K crossingHeight^2 with K = 3.3 + 11 (1 - w) (the mean squared slope of the
    // unfiltered pattern per unit crossing height: 2.6 to 4.1 for w = 1, 4.0 to 6.3 for w = 0.85,
    // 5.9 to 9.0 for w = 0.6 over every pattern and roundness in [0.5, 2]; test_core_fabric).
    if (fade > 0.0f) {
        float slopeVariance =
            fade * (3.3f + 11.0f * (1.0f - w)) * crossingHeight * crossingHeight;
        float alpha = o.roughness * o.roughness;
        o.roughness = min(sqrt(sqrt(alpha * alpha + slopeVariance)), 1.0f);
    }
    return o;
}

// What the Knit node outputs at one point.
struct VelvetKnit {
    vec3 color;
    float height;
    vec3 normal;
    vec2 direction; // tangent-space direction of the loop's leg seen
    float occlusion;
};

// Plain jersey (single jersey, stockinette), its technical face: each stitch is a loop whose two
// legs lean towards each other at its foot, so the face shows columns (wales, counted along u) of
// V shapes stacked in rows (courses, counted along v) (Spencer, "Knitting Technology", 3rd ed.,
// ch. 2). A leg is a yarn of the given width (a fraction of half a wale) along the line
// fu = 1/2 +- (1/4 + lean (fv - 1/2) / 2), rising in the middle of the course and dipping where
// it passes under the loop heads of the courses above and below.
VelvetKnit velvetKnit(vec2 uv, vec2 density, float width, float roundness, float lean,
                      float stitchHeight, vec3 color) {
    vec2 d = max(density, vec2(1e-3f));
    float w = clamp(width, 0.05f, 1.0f);
    float X = uv.x * d.x;
    float Y = uv.y * d.y;
    float fu = X - floor(X);
    float fv = Y - floor(Y);
    float side = fu < 0.5f ? -1.0f : 1.0f;
    float k = 0.5f * clamp(lean, 0.0f, 1.0f) * side;
    float centre = 0.5f + 0.25f * side + k * (fv - 0.5f);
    float x = (fu - centre) / (0.25f * w);
    float pSlope;
    float p = velvetYarnProfile(x, roundness, pSlope);
    float level = 0.55f + 0.45f * sin(3.14159265f * fv);
    float levelSlope = 0.45f * 3.14159265f * cos(3.14159265f * fv);
    VelvetKnit o;
    vec2 grad = vec2(0.0f);
    if (abs(x) < 1.0f) {
        o.height = level * p;
        grad = vec2(level * pSlope * d.x / (0.25f * w),
                    (p * levelSlope - level * pSlope * k / (0.25f * w)) * d.y);
        o.color = color * (0.7f + 0.3f * o.height);
    } else {
        o.height = 0.0f;
        o.color = 0.45f * color;
    }
    o.direction = normalize(vec2(k / d.x, 1.0f / d.y));
    grad = grad * (stitchHeight * 2.0f / (d.x + d.y));
    o.normal = normalize(vec3(-grad.x, -grad.y, 1.0f));
    o.occlusion = 0.45f + 0.55f * o.height;
    return o;
}

// What the Fibre fuzz node outputs at one point.
struct VelvetFuzz {
    vec3 color;
    float roughness;
    float sheen;
    float mask;
};

// Hairiness: the loose fibre ends that stand out of a spun yarn and lie roughly along it. Gradient
// noise in a frame aligned with the yarn, stretched `stretch` times along it, so its streaks run
// with the fibres; where it is high the surface takes the fuzz colour (the fibres' own colour
// seen without the yarn's shadowing), more roughness and more sheen (the fibres that stand out
// of the surface are what a sheen lobe models: Estevez & Kulla 2017).
VelvetFuzz velvetFuzz(vec2 uv, vec2 direction, vec3 baseColor, float roughness, vec3 fuzzColor,
                      float density, float stretch, float amount) {
    vec2 dir = length(direction) > 1e-6f ? normalize(direction) : vec2(0.0f, 1.0f);
    vec2 across = vec2(dir.y, -dir.x);
    vec2 p = vec2(dot(uv, across), dot(uv, dir) / max(stretch, 1.0f)) * density;
    float n = velvetGraphPerlin01(p);
    VelvetFuzz o;
    o.mask = clamp(amount, 0.0f, 1.0f) * smoothstep(0.4f, 0.75f, n);
    o.color = mix(baseColor, fuzzColor, 0.6f * o.mask);
    o.roughness = clamp(roughness + 0.2f * o.mask, 0.0f, 1.0f);
    o.sheen = o.mask;
    return o;
}

// What the Pile node outputs at one point.
struct VelvetPile {
    vec3 normal;
    float sheen;
    float roughness;
    float crush; // [0, 1]: how flattened the pile is here
};

// Cut pile (velvet, velour): fibres standing up from the ground weave, all leaning towards the
// lay direction (`angle`, degrees counter-clockwise from +U) by `lean` (the tangent of their tilt),
// so the shading normal of the fibre tips tilts that way. Crushed velvet presses patches of the
// pile flat in other directions: an FBM decides where (patches `scale` per UV unit), a second
// noise which way, and a crushed patch lies at tilt 1.2 (50 degrees), rotated up to +-180 degrees
// times `crush`. Upright pile keeps its full sheen; flattened fibres reflect more like a smooth
// surface, so crushed patches trade sheen for lower roughness.
VelvetPile velvetPile(vec2 uv, float angle, float lean, float crush, float scale) {
    float c = clamp(crush, 0.0f, 1.0f);
    float patchValue = velvetGraphFbm(uv * scale, 4.0f, 2.0f, 0.5f);
    float turn = velvetGraphPerlin01(uv * scale + vec2(31.7f, 11.3f)) - 0.5f;
    VelvetPile o;
    o.crush = c * smoothstep(0.45f, 0.6f, patchValue);
    float a = radians(angle) + o.crush * turn * 6.28318531f;
    float tilt = mix(max(lean, 0.0f), 1.2f, o.crush);
    o.normal = normalize(vec3(tilt * cos(a), tilt * sin(a), 1.0f));
    o.sheen = 1.0f - 0.6f * o.crush;
    o.roughness = mix(0.8f, 0.45f, o.crush);
    return o;
}

)
