// A Velvet material preset (docs/file-formats.md, `velvet.material`) as MeshPhysicalMaterial
// parameters, so the peer draws the material Velvet draws. Pure data in, data out (no three.js),
// so it runs in the page and in node alike.
//
// Omitted parameters take Velvet's defaults, read from the shipped JSON Schema
// (resources/schemas/material.schema.json, generated from the same metadata Velvet's reader
// uses) rather than copied here, so a changed default cannot drift between the two renderers.

const LOBES = ['base', 'emission', 'clearcoat', 'sheen', 'anisotropy'];

// Velvet's BRDF term choices that three.js's fixed terms do not draw. three.js uses GGX,
// height-correlated Smith visibility, Schlick Fresnel, Lambert diffuse and a Charlie sheen with
// Neubelt visibility, whatever the preset says.
const THREE_TERMS = {
  distribution: 'ggx',
  visibility: 'smith-ggx-correlated',
  fresnel: 'schlick',
  diffuse: 'lambert',
  sheen: 'charlie-neubelt',
};

/** Every parameter of @p preset, omitted ones filled from @p schema's defaults. */
export function resolvedPreset(preset, schema) {
  const def = schema.$defs.material.properties;
  const lobes = {};
  for (const lobe of LOBES) {
    const props = def.lobes.properties[lobe].properties;
    const given = preset.lobes?.[lobe] ?? {};
    lobes[lobe] = {};
    for (const [key, meta] of Object.entries(props))
      lobes[lobe][key] = given[key] ?? meta.default;
  }
  const brdf = {};
  for (const [key, meta] of Object.entries(def.brdf.properties))
    brdf[key] = preset.brdf?.[key] ?? meta.default;
  return { name: preset.name, lobes, brdf, textures: preset.textures ?? {} };
}

/**
 * MeshPhysicalMaterial parameters for @p preset. Colours are scene-linear Rec.709 triples, as
 * Velvet stores them (the page makes them THREE.Color in LinearSRGBColorSpace). `notes` lists
 * what the peer does not draw as Velvet does.
 */
export function physicalParams(preset, schema) {
  const { lobes: l, brdf, textures } = resolvedPreset(preset, schema);
  const params = {
    color: l.base.color,
    metalness: l.base.metallic,
    roughness: l.base.roughness, // both perceptual (alpha = roughness²)
    specularIntensity: l.base.specularWeight, // KHR_materials_specular
    specularColor: l.base.specularColor,
    ior: l.base.ior,
    emissive: l.emission.color,
    emissiveIntensity: l.emission.strength,
    clearcoat: l.clearcoat.weight,
    clearcoatRoughness: l.clearcoat.roughness,
    // three.js multiplies sheenColor by sheen, as Velvet exports sheenColorFactor = weight × colour.
    sheen: l.sheen.weight,
    sheenColor: l.sheen.color,
    sheenRoughness: l.sheen.roughness,
    anisotropy: l.anisotropy.strength,
    anisotropyRotation: (l.anisotropy.rotation * Math.PI) / 180,
  };
  const notes = [];
  for (const [term, drawn] of Object.entries(THREE_TERMS))
    if (brdf[term] !== drawn) notes.push(`brdf.${term}: Velvet ${brdf[term]}, three.js ${drawn}`);
  for (const slot of Object.keys(textures)) notes.push(`textures.${slot}: not drawn by the peer`);
  return { params, notes };
}
