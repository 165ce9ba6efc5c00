// The leather Grain node's functions, in the same common subset of GLSL 4.50 and C++20 with GLM as
// fabric_source.inl (whose conventions hold here) and built the same way: fabric_nodes.cpp appends
// this text to the HelperFabric GLSL, fabric.cpp compiles it as the C++ twin. It calls pcg2d, the
// shaders' integer hash (common_hash.glsl, emitted with the noise helpers; its twin in fabric.cpp).
//
// Not a header: included only by those two files, each of which defines VELVET_FABRIC_SOURCE.
//
// Pebbled leather, the grain side of a hide (full grain, "pebble" or "Scotch grain" embossing), is
// a mosaic of slightly domed cells parted by narrow creases. The cells are those of a cellular
// (Voronoi) texture, Worley 1996, "A Cellular Texture Basis Function", SIGGRAPH: one feature point
// jittered inside each cell of a grid of `scale` cells per UV unit, each point owning the plane
// closer to it than to any other. The height is a profile of e, the distance to the cell's border
// (the nearest bisector between its point and a neighbour's; Quilez 2012, "Voronoi edges"), in
// cell spacings (1 / scale), so the cells stay `scale` per UV unit whatever their irregularity.
VELVET_FABRIC_SOURCE(

// A cell's feature point: the grid cell g (whole numbers) plus a jitter in [-1/2, 1/2]^2 times
// the irregularity, hashed from g (0: a square grid; 1: anywhere in the cell).
vec2 velvetGrainPoint(vec2 g, float irregularity) {
    uvec2 h = pcg2d(uvec2(ivec2(g)));
    vec2 r = vec2(float(h.x >> 8u), float(h.y >> 8u)) * (1.0f / 16777216.0f);
    return g + vec2(0.5f) + clamp(irregularity, 0.0f, 1.0f) * (r - vec2(0.5f));
}

// The crease's shoulder: c = 1 - (1 - t)^2, t = e / creaseWidth clamped to 1 (a V-shaped crease
// whose sides round into the cell's top), and its derivative dc/de.
float velvetGrainCrease(float e, float creaseWidth, VELVET_OUT(float) slope) {
    float w = max(creaseWidth, 0.01f);
    float t = min(e / w, 1.0f);
    slope = 2.0f * (1.0f - t) / w;
    return 1.0f - (1.0f - t) * (1.0f - t);
}

// The height at border distance e: the crease's shoulder times the cell's dome,
// (1 - dome) + dome (1 - (1 - e)^2) (the same parabola over one cell spacing, so it rises to the
// cell's middle and is never flat for e < 1), and its derivative dh/de.
float velvetGrainHeight(float e, float creaseWidth, float dome, VELVET_OUT(float) slope) {
    float cSlope;
    float c = velvetGrainCrease(e, creaseWidth, cSlope);
    float s = min(e, 1.0f);
    float d = clamp(dome, 0.0f, 1.0f);
    float k = 1.0f - d + d * (1.0f - (1.0f - s) * (1.0f - s));
    slope = cSlope * k + c * d * 2.0f * (1.0f - s);
    return c * k;
}

// The means over the cells of the Grain's height, crease profile and squared slope dh/de, what a
// pixel spanning many cells should show. A model of the node's own statements: a cell of unit
// area taken as a polygon of inradius r, whose points lie at border distance > e on a fraction
// (1 - e / r)^2 of its area (exact for any polygon with an inscribed circle), so e has the density
// 2 (1 - e / r) / r on [0, r], less the smooth minimum's dip (0.034 on average); r = 0.48 for the
// square cells of a regular grid, 0.46 for fully jittered ones, whose mixed sizes put more area
// near a border (both fitted to the averaged pattern over crease widths 0.08 to 0.3 and domes 0
// to 1: within 0.01). The integral is a 32-point midpoint sum. The smooth minimum's gradient is
// shorter than 1 where bisectors meet (a mean of unit normals): the measured mean slope^2 is 0.62
// to 0.74 of the model's, hence 0.68. test_core_fabric measures
// the three against the averaged unfiltered pattern.
struct VelvetGrainMean {
    float height;
    float crease;
    float slope2;
};

VelvetGrainMean velvetGrainMean(float irregularity, float creaseWidth, float dome) {
    float r = 0.48f - 0.02f * clamp(irregularity, 0.0f, 1.0f);
    VelvetGrainMean m;
    m.height = 0.0f;
    m.crease = 0.0f;
    m.slope2 = 0.0f;
    for (int k = 0; k < 32; ++k) {
        float e = (float(k) + 0.5f) * r / 32.0f;
        float weight = 2.0f * (1.0f - e / r) / 32.0f;
        if (e > 0.034f) {
            float cSlope;
            float hSlope;
            m.crease += weight * velvetGrainCrease(e - 0.034f, creaseWidth, cSlope);
            m.height += weight * velvetGrainHeight(e - 0.034f, creaseWidth, dome, hSlope);
            m.slope2 += weight * hSlope * hSlope;
        }
    }
    m.slope2 = 0.68f * m.slope2;
    return m;
}

// What the Grain node outputs at one point.
struct VelvetGrain {
    vec3 color;      // creaseColor in the creases, color on the cells' tops (by height)
    float height;    // [0, 1]
    vec3 normal;     // tangent space
    float roughness; // creaseRoughness in the creases, roughness on the tops (by height)
    float cavity;    // [0, 1]: 1 at the bottom of a crease, 0 past its shoulder
    float occlusion; // 1 - 0.6 cavity
    float cell;      // a value in [0, 1) per cell
};

VelvetGrain velvetGrain(vec2 uv, float scale, float irregularity, float creaseWidth, float dome,
                        float depth, vec3 color, vec3 creaseColor, float roughness,
                        float creaseRoughness, vec2 footprint) {
    float s = max(scale, 1e-3f);
    vec2 x = uv * s;
    vec2 g = floor(x);
    // The nearest feature point (Worley's F1): with the jitter inside its own grid cell, it lies
    // in the 3 x 3 cells around x.
    vec2 nearest = velvetGrainPoint(g, irregularity);
    vec2 nearestCell = g;
    float best = 1e30f;
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            vec2 c = g + vec2(float(i), float(j));
            vec2 p = velvetGrainPoint(c, irregularity);
            float dd = dot(p - x, p - x);
            if (dd < best) {
                best = dd;
                nearest = p;
                nearestCell = c;
            }
        }
    }
    // The distance to the cell's border: the nearest of the bisectors between the nearest point
    // and its neighbours (Quilez's second pass, over the 5 x 5 cells around the nearest one),
    // taken as a smooth minimum, -k ln sum exp(-d_i / k) with k = 0.1 cell spacings (Quilez
    // 2013, "smooth minimum"), so the cells' domes round over their ridges instead of meeting in
    // the kinks of a hip roof, and their corners round off where three cells meet: pebbles, not
    // paving stones. Its gradient
    // is -sum w_i n_i, w_i = exp(-d_i / k) / sum, n_i a bisector's normal out of the cell. The sum
    // is kept relative to the smallest d_i so far (rescaled when it drops) so exp cannot overflow.
    float k = 0.1f;
    float e = 1e30f;
    float sum = 0.0f;
    vec2 awaySum = vec2(0.0f);
    for (int j = -2; j <= 2; ++j) {
        for (int i = -2; i <= 2; ++i) {
            if (i == 0 && j == 0)
                continue;
            vec2 p = velvetGrainPoint(nearestCell + vec2(float(i), float(j)), irregularity);
            vec2 ab = p - nearest;
            float len = length(ab);
            if (len < 1e-5f)
                continue;
            vec2 n = ab / len;
            float dist = dot(0.5f * (nearest + p) - x, n);
            if (dist < e) {
                float rescale = sum > 0.0f ? exp((dist - e) / k) : 0.0f;
                sum = sum * rescale + 1.0f;
                awaySum = awaySum * rescale + n;
                e = dist;
            } else {
                float wi = exp((e - dist) / k);
                sum += wi;
                awaySum += wi * n;
            }
        }
    }
    e = e - k * log(sum);
    vec2 away = awaySum / sum;
    // The smooth minimum dips below 0 along the border: the crease's floor.
    if (e <= 0.0f)
        away = vec2(0.0f);
    e = max(e, 0.0f);
    float hSlope;
    float h = velvetGrainHeight(e, creaseWidth, dome, hSlope);
    float cSlope;
    float c = velvetGrainCrease(e, creaseWidth, cSlope);
    uvec2 id = pcg2d(uvec2(ivec2(nearestCell)) + uvec2(7919u, 104729u));
    VelvetGrain o;
    o.cell = float(id.x >> 8u) * (1.0f / 16777216.0f);

    // Filtering by the pixel's footprint, as the Weave (fabric_source.inl; Ebert et al.,
    // "Texturing and Modeling", ch. 2): where a pixel spans more than a quarter of a cell the
    // creases alias, so the outputs fade to the cells' means, reached at three quarters of a
    // cell; the slopes that fade out of the normal go into the roughness (Toksvig 2005).
    float cells = max(footprint.x, footprint.y) * s;
    float fade = smoothstep(0.25f, 0.75f, cells);
    float slope2 = 0.0f;
    if (fade > 0.0f) {
        VelvetGrainMean mean = velvetGrainMean(irregularity, creaseWidth, dome);
        h = mix(h, mean.height, fade);
        c = mix(c, mean.crease, fade);
        slope2 = fade * mean.slope2;
    }
    o.height = h;
    o.cavity = 1.0f - c;
    o.occlusion = 1.0f - 0.6f * o.cavity;
    o.color = mix(creaseColor, color, h);
    // The physical height is depth * h in cell spacings (1 / scale UV units), so its gradient in
    // UV is depth * dh/de * (-away): the scale cancels, as the Weave's thread spacing does.
    vec2 grad = -away * (hSlope * depth * (1.0f - fade));
    o.normal = normalize(vec3(-grad.x, -grad.y, 1.0f));
    o.roughness = clamp(mix(creaseRoughness, roughness, h), 0.0f, 1.0f);
    if (fade > 0.0f) {
        float alpha = o.roughness * o.roughness;
        o.roughness = min(sqrt(sqrt(alpha * alpha + slope2 * depth * depth)), 1.0f);
    }
    return o;
}

)
