-- A transmissive material (glTF's KHR_materials_transmission and KHR_materials_volume; the seeds
-- have no refraction model): the standard base whose diffuse lobe gives way, by the transmission
-- factor, to light from behind the surface — the opaque frame (sky, opaque surfaces, lines)
-- copied after it is drawn and filtered into mips (scripts/render_loop.lua's `opaque`), read where
-- the view ray, refracted by the IOR, leaves a volume `thickness` deep, at a mip that widens with
-- the roughness, and tinted by the volume's Beer–Lambert transmittance. What the specular lobe
-- reflects (its split-sum albedo) is not transmitted. A surface that needs what lies behind it
-- has no G-buffer pixel: `forward = true`, so the forward pass draws every scene material of it
-- (the glTF loader makes them blended; a Lua scene gives alpha = "blend").
--
-- The layout is the unpacked form the forward shading takes (it also fits the G-buffer targets, as
-- every layout of the pipeline must): the metal mask in GB0's two spare bits (glTF transmission
-- is a dielectric's; a metal reflects), the transmission factor beside the base colour, the
-- volume's transmittance over its thickness (attenuationColor^(thickness / attenuationDistance))
-- with the reflectance (IOR 1.5: 0.5), and the thickness (world units) beside the emission.
local rg = require "rg"
local ibl = require "ibl"  -- lit by the distant light probe, its specular albedo from the DFG table
require "disney"

rg.layout "transmission" {
    { "GB0", "rgb10a2",    { "normal:oct:20", "smoothness:unorm:10", "metalMask:unorm:2" } },
    { "GB1", "rgba8_srgb", { "baseColor:srgb:24", "transmission:unorm:8" } },
    { "GB2", "rgba8",      { "volumeColor:unorm:8x3", "reflectance:unorm:8" } },
    { "GB3", "rgba16f",    { "emissive:float:16x3", "thickness:float:16" } },
}

-- A path without a stencil class: the forward pass's only (no deferred pass lights it, and it takes
-- none of the 15 classes).
rg.path "transmission" { shading = "transmission_shading.glsl",
                         doc = "the standard BRDF, its diffuse replaced by the refracted opaque frame" }
rg.material "transmission" {
    layout = "transmission", path = "transmission", surface = "materials/transmission.glsl",
    forward = true,
    -- glTF's transmissionFactor, thicknessFactor (0: thin-walled, no refraction or absorption),
    -- attenuationDistance (0: none, glTF's +∞) and attenuationColor.
    params = { transmissionFactor = 1.0, thicknessFactor = 0.0, attenuationDistance = 0.0,
               attenuationColorR = 1.0, attenuationColorG = 1.0, attenuationColorB = 1.0 },
    -- glTF's transmissionTexture (R) and thicknessTexture (G), times the factors.
    textures = { "transmissionMap", "thicknessMap" },
    decals = false,  -- a blended surface has no G-buffer pixel for a decal to change
    doc = "glass and liquids: the opaque frame behind, refracted and absorbed (glTF KHR_materials_transmission, _volume)",
}
