-- Image-based lighting from the scene's distant light probe (seed 002 §4.9; DESIGN §3).
--
--   local ibl = require "ibl"        -- declares the probe's resources and its filtering passes
--   rg.pass "lighting_x" (ibl.lit { kind = "fullscreen", shader = ..., reads = { ... }, ... })
--
-- The filtering (§4.9.2) runs once, when the pipeline is built or the scene (its environment)
-- changes — `cadence = "once"` — never per frame, into persistent resources:
--   env_cube       the environment (graph/scene/environment.h: an HDR file, a colour or the
--                  Preetham sky of the scene's sun) resampled into a cube, then its mip chain;
--   env_hot        the environment's hot texels (a sun) listed, and the cube without them (env_smooth,
--                  then its mip chain);
--   env_prefilter  the specular pre-filtered cube, one mip per roughness (mip = sqrt(α_lin) · (mips − 1)),
--                  GGX importance sampling of env_smooth with filtered samples, plus the hot texels exactly;
--   env_irradiance the diffuse probe as 9 spherical-harmonic coefficients;
--   dfg_table      the 128×128 DFG table: the split-sum's two specular terms, the Disney diffuse
--                  and the sheen lobe's albedo (materials/sheen.lua).
-- `ibl.lit` makes a lighting pass read them (lib/ibl.glsl with RG_IBL: the distant probe's diffuse
-- and specular along the seed's dominant directions, with specular occlusion from AO).
local rg = require "rg"
local lighting = require "lighting"

local ibl = {}

ibl.source_size = 256   -- the cube the environment is resampled into (texels per face)
ibl.specular_size = 256 -- the pre-filtered cube (seed 002 §4.9.2: 256–512); 9 mips: linear roughness 0, 1/64, 4/64 .. 1

rg.resource "env_source" { format = "rgba16f", size = { ibl.source_size, ibl.source_size }, cube = true, mips = "full", persistent = true,
    doc = "the environment as a cube with its mip chain (nits)" }
rg.resource "env_specular" { format = "rgba16f", size = { ibl.specular_size, ibl.specular_size }, cube = true, mips = 9, persistent = true,
    doc = "the specular pre-filtered probe: mip m for linear roughness (m / 8)²" }
rg.resource "env_smooth" { format = "rgba16f", size = { ibl.source_size, ibl.source_size }, cube = true, mips = "full", persistent = true,
    doc = "env_source without its hot texels (env_hot), with its mip chain: what the pre-filter samples" }
rg.buffer "env_hot" { size = 16 + 4096 * 32, persistent = true,
    doc = "the environment's hot texels (a sun): count, then direction and solid angle, radiance per texel" }
rg.buffer "env_sh" { size = 9 * 16, persistent = true, doc = "the environment's radiance as order-2 spherical harmonics (9 RGB)" }
rg.resource "dfg" { format = "rgba16f", size = { 128, 128 }, persistent = true,
    doc = "pre-integrated DFG: x, y the split-sum specular terms, z the Disney diffuse, over (N·V, linear roughness); w the sheen lobe's albedo over (N·V, sheen roughness)" }

rg.pass "env_cube" {
    kind = "compute", shader = "ibl/env_cube.comp", writes = { { "env_source", as = "storage" } }, cadence = "once",
}
rg.pass "env_mips" {  -- the cube's mip chain from mip 0 (a compute pass: lavapipe's blits recompile every run)
    kind = "compute", shader = "post/downsample.comp", writes = { { "env_source", as = "storage_rw" } }, bind = { target = "env_source" },
    defines = { RG_LAYERED = true, RG_CUBE = true }, per_mip = true, cadence = "once",
}
rg.pass "env_irradiance" {
    kind = "compute", shader = "ibl/env_sh.comp", reads = { "env_source" },
    writes = { { "env_sh", as = "storage" } }, groups = { 1, 1, 1 }, cadence = "once",
}
rg.pass "env_hot" {  -- the hot texels out of the cube the pre-filter samples, listed for it to add exactly
    kind = "compute", shader = "ibl/env_hot.comp", reads = { "env_source", { "env_sh", as = "uniform" } },
    writes = { { "env_smooth", as = "storage" }, { "env_hot", as = "storage" } }, groups = { 1, 1, 1 }, cadence = "once",
}
rg.pass "env_smooth_mips" {
    kind = "compute", shader = "post/downsample.comp", writes = { { "env_smooth", as = "storage_rw" } }, bind = { target = "env_smooth" },
    defines = { RG_LAYERED = true, RG_CUBE = true }, per_mip = true, cadence = "once",
}
rg.pass "env_prefilter" {
    kind = "compute", shader = "ibl/env_prefilter.comp", reads = { "env_source", "env_smooth", "env_hot" },
    writes = { { "env_specular", as = "storage" } }, per_mip = true, cadence = "once",
}
rg.pass "dfg_table" {
    kind = "compute", shader = "ibl/dfg.comp", writes = { { "dfg", as = "storage" } }, cadence = "once",
}

-- A lighting pass's declaration, lit by the distant probe too: adds the probe's resources to its
-- reads and RG_IBL to its defines. Returns the table it was given.
function ibl.lit(pass)
    return lighting.extend(pass, { "env_specular", { "env_sh", as = "uniform" }, "dfg" }, "RG_IBL")
end

return ibl
