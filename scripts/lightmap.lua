-- Baked global illumination: the scene's SG lightmap (seed 003, "SG Lightmaps"; graph/bake).
--
--   local lightmap = require "lightmap"   -- declares the pipeline's switch for it
--
-- A scene that declares scene.lightmap (scripts/scenes/README.md) gets it baked — or read from the
-- cache — when it is loaded, and every scene pass then sees RG_SCENE_LIGHTMAP: the G-buffer pass
-- adds the surface's radiosity from the lightmap (shaders/lib/lightmap.glsl: the SG irradiance at
-- the shaded normal × the diffuse albedo / π) to its emission, and the lighting passes leave out
-- the distant probe's diffuse light, which the lightmap holds. Lights the scene marks `baked` are
-- in the lightmap and dark in the real-time light loop. The G-buffer pass also writes the
-- lightmap's specular radiance along each pixel's reflection into `lightmap_specular`
-- (render_loop.lua), which the reflection composition (reflections.lua) takes where SSR and the
-- local probes leave off — the distant probe's share — unless lightmap_specular is false.
local rg = require "rg"

local lightmap = {}

-- Set by a module whose G-buffer pass writes `lightmap_specular` (render_loop.lua); the reflection
-- composition (reflections.lua) reads it only then.
lightmap.gbuffer_writes_specular = false

rg.param "lightmap" { type = "boolean", default = true,
    doc = "use the scene's baked SG lightmap (scene.lightmap) when it has one; read when the scene loads" }
rg.param "lightmap_specular" { type = "boolean", default = true,
    doc = "with a lightmap, reflect its light (the SG lobes through the GGX lobe) where SSR and the local probes leave off, instead of the distant probe; off: the G-buffer does not compute it" }

return lightmap
