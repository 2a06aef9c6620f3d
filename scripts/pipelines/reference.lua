-- The in-engine reference mode (seed 000 §2.3; seed 002 §4.7): the same G-buffer as deferred.lua,
-- lit by brute-force Monte Carlo integration of every light of the scene instead of the real-time
-- approximations, so that `rgraph compare deferred.exr reference.exr` measures only the error of
-- the light approximations (same BRDF, same G-buffer, no shadowing in either — or, with
-- reference_shadows = true, shadow rays against the scene's triangles: the ground truth for the
-- shadow maps). Progressive: each
-- frame adds `reference_samples` samples per pixel to a persistent running mean, so
--
--   rgraph render --pipeline scripts/pipelines/reference.lua --scene S --frames 256 --out ref.exr
--
-- converges as 1/√frames. Point and spot lights (delta lights) are evaluated exactly; sun, sphere,
-- disk, rect and tube lights are sampled (light sample + BRDF sample, multiple importance sampling).
-- Clear coat is integrated with its coat lobe, the two-colour material from its diffuse and f0
-- colours; blended materials are drawn by the real-time forward pass, not integrated. See
-- shaders/passes/reference.comp and scripts/README.md.
local rg = require "rg"
local post = require "post"
local loop = require "render_loop"  -- the materials, G-buffer, scene pass and decals of deferred.lua

post.params { exposure_mode = "auto" }
post.exposure_state()
rg.param "reference_samples" { type = "integer", default = 4, min = 1, max = 1024,
                               doc = "samples per pixel per frame (each: one BRDF sample + one sample of every sampled light)" }
rg.param "reference_seed" { type = "integer", default = 0, min = 0, max = 16777215,
                            doc = "random seed (PCG hash of pixel, frame and this; samples follow in the stream)" }
rg.param "reference_forward" { type = "boolean", default = true,
                               doc = "draw blended materials with deferred.lua's real-time forward pass (not integrated)" }
rg.param "reference_shadows" { type = "boolean", default = false,
                               doc = "shadow rays through the scene's opaque triangles for every light and environment sample (the ground truth for shadowed lights; off: unoccluded like the real-time light approximations it checks)" }
rg.param "reference_strategy" { type = "choice", default = "mis", choices = { "mis", "light", "brdf" },
                                doc = "mis: light (and environment) + BRDF samples, power heuristic; light / brdf: one strategy alone (to check each converges to the same image)" }

-- The running mean of the unexposed luminance (cd/m²) and, in alpha, how many frames it holds:
-- carried over frames, zero when created and whenever the session resets its history.
-- Read and written by the same pass (storage_rw: the graph keeps its contents and orders the access).
rg.resource "reference_accum" { format = "rgba32f", persistent = true }

-- Instead of deferred.lua's lighting passes: every pixel with geometry (depth < 1), whatever its
-- stencil class, is integrated here — the standard BRDF, plus the coat lobe of materialId 1
-- (materials/clearcoat_shading.glsl's BRDF per direction), the two-colour material's diffuse
-- and f0 colours (materials/two_colour.lua) and the sheen material's lobe (materials/sheen.lua,
-- its albedo from the DFG table); the far plane gets 0. The pass keeps the name of the
-- standard lighting pass it replaces: materials/clearcoat.lua and two_colour.lua insert their
-- lighting passes after it, and rg.frame below turns those real-time passes off.
rg.pass "lighting_standard" {
    kind = "compute", shader = "passes/reference.comp", dispatch = "hdr",
    reads = { "GB0", "GB1", "GB2", "GB3", "depth", { "depth", as = "stencil" }, { "exposure", as = "storage" }, "dfg" },
    writes = { { "hdr", as = "storage" }, { "reference_accum", as = "storage_rw", load = true } },
}

-- The sky, then blended materials: not integrated — by default the forward pass draws them as
-- deferred.lua does (the real-time light loop), so they match in both and `rgraph compare` still
-- measures the opaque surfaces behind them; reference_forward = false leaves them out.
loop.sky_and_forward()

post.chain { input = "hdr", output = "display" }
rg.output { display = "display", hdr = "hdr", exposure = "exposure" }

function rg.frame(ctx)
    ctx.pass("lighting_clearcoat").enabled = false   -- the reference lights clear coat itself
    ctx.pass("lighting_two_colour").enabled = false  -- and the two-colour material
    ctx.pass("lighting_sheen").enabled = false       -- and the sheen material
    ctx.pass("light_culling").enabled = false        -- nothing here reads tile lists
    ctx.pass("forward").enabled = ctx.params.reference_forward
    loop.frame(ctx)  -- as deferred.lua: no decals, no decal passes
end
