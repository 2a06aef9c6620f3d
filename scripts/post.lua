-- The physical camera and the post chain (seed 002 §5.1–§5.3): temporal anti-aliasing (TAA) or
-- FXAA, auto-exposure from a log-luminance histogram, an energy-conserving bloom, tone mapping, the
-- exact sRGB transfer function. A pipeline uses it as
--
--   local post = require "post"
--   post.params { exposure_mode = "auto" }   -- camera and post parameters (rg.param)
--   post.exposure_state()                    -- the persistent `exposure` buffer HDR passes read
--   ... passes that render `hdr` (luminance × pre-exposure, see shaders/lib/exposure.glsl) ...
--   post.at("display", "vignette", { kind = "fullscreen", shader = ... })  -- a team's pass, see below
--   post.chain { input = "hdr", output = "display", depth = "depth" }  -- depth: TAA's reprojection
--   rg.output { display = "display", hdr = "hdr", exposure = "exposure" }
--   function rg.frame(ctx) post.frame(ctx) end  -- the `antialiasing` parameter's passes
local rg = require "rg"
local post = {}

-- The chain's insertion points, in the order the image passes them; what the image is there, and
-- the format of the image a pass inserted there writes:
--   "linear"          after lighting, the sky, blended surfaces and the reflections' history, before
--                     bloom and metering: linear HDR, luminance × this frame's pre-exposure
--                     (shaders/lib/exposure.glsl; a pass that scales it scales what is metered), rgba16f
--   "exposed"         after exposure and bloom, before the tone curve: linear, exposed (1 is the
--                     curve's input for a white of the camera's exposure), rgba16f
--   "display_linear"  after the tone curve, before the sRGB encode and the dither: display-referred
--                     linear, 0..1, rgba16f
--   "display"         after FXAA: the display image, sRGB-encoded values, rgba8 — what rg.output shows
post.points = { "linear", "exposed", "display_linear", "display" }
local point_formats = { linear = "rgba16f", exposed = "rgba16f", display_linear = "rgba16f", display = "rgba8" }
post.inserted = { linear = {}, exposed = {}, display_linear = {}, display = {} }

-- Puts a team's pass at an insertion point, after those put there before it; call it before
-- post.chain. `pass` is an rg.pass declaration without the image: the chain adds the image before
-- the point to its reads, bound as `source` (`uniform sampler2D source;`), and makes it write the
-- next image, a resource of the point's format named after the pass. Its own reads, binds,
-- uniforms and defines are kept. The tone mapping is one pass while nothing is put at "exposed" or
-- "display_linear"; each of them, when used, splits it there (one full-screen pass more, ~1.5 ms
-- at 1280×720 on lavapipe).
function post.at(point, name, pass)
    if post.inserted[point] == nil then
        error("post.at: unknown insertion point '" .. tostring(point) .. "'; expected one of: " .. table.concat(post.points, ", "), 2)
    end
    if type(name) ~= "string" or type(pass) ~= "table" then
        error("post.at: expected post.at(POINT, \"name\", { kind = ..., shader = ... })", 2)
    end
    if post.chained then error("post.at: '" .. name .. "' comes after post.chain; put it before", 2) end
    table.insert(post.inserted[point], { name = name, pass = pass })
end

-- Declares the passes put at `point`, from `source` on; returns the image the last one writes
-- (`source` when there are none). The last one writes `final` when it is given.
local function insert_passes(point, source, final)
    local list = post.inserted[point]
    for i, entry in ipairs(list) do
        local image = (i == #list and final) or entry.name
        rg.resource(image) { format = point_formats[point] }
        local p = {}
        for k, v in pairs(entry.pass) do p[k] = v end
        p.reads = { source }
        for _, r in ipairs(entry.pass.reads or {}) do table.insert(p.reads, r) end
        p.writes = { image }
        p.bind = { source = source }
        for k, v in pairs(entry.pass.bind or {}) do p.bind[k] = v end
        rg.pass(entry.name)(p)
        source = image
    end
    return source
end

local function log2(x) return math.log(x, 2) end

-- EV100 = log2(N² / t · 100 / S) − EC (seed 002 §5.1.1).
function post.ev100(aperture, shutter, iso, ec)
    return log2(aperture * aperture / shutter * 100 / iso) - (ec or 0)
end

-- Declares the camera and post parameters; `o` overrides defaults. The default camera is
-- "Sunny 16": f/16, 1/125 s, ISO 100 (EV100 ≈ 15), right for a scene in full sun.
function post.params(o)
    o = o or {}
    local aperture, shutter, iso, ec = o.aperture or 16, o.shutter or 1 / 125, o.iso or 100, o.ec or 0
    rg.param "exposure_mode" { type = "choice", default = o.exposure_mode or "auto", choices = { "auto", "manual" },
                               doc = "auto: metered from a histogram; manual: from aperture, shutter and ISO" }
    rg.param "aperture" { type = "number", default = aperture, min = 0.5, max = 128, doc = "relative aperture N, f-stops" }
    rg.param "shutter" { type = "number", default = shutter, min = 1e-6, max = 3600, doc = "shutter time t, seconds" }
    rg.param "iso" { type = "number", default = iso, min = 1, max = 409600, doc = "sensor sensitivity S, ISO" }
    rg.param "ec" { type = "number", default = ec, min = -16, max = 16, doc = "exposure compensation, stops" }
    rg.param "auto_low" { type = "number", default = o.auto_low or 10, min = 0, max = 100, doc = "auto-exposure: lowest percentile metered" }
    rg.param "auto_high" { type = "number", default = o.auto_high or 90, min = 0, max = 100, doc = "auto-exposure: highest percentile metered" }
    rg.param "speed_up" { type = "number", default = o.speed_up or 3, min = 0, max = 1000, doc = "adaptation speed towards higher EV, 1/s" }
    rg.param "speed_down" { type = "number", default = o.speed_down or 1, min = 0, max = 1000, doc = "adaptation speed towards lower EV, 1/s" }
    rg.param "min_ev100" { type = "number", default = o.min_ev100 or -8, min = -32, max = 32 }
    rg.param "max_ev100" { type = "number", default = o.max_ev100 or 24, min = -32, max = 32 }
    rg.param "frame_time" { type = "number", default = o.frame_time or 1 / 60, min = 0, max = 10, doc = "seconds per frame (fixed)" }
    rg.param "initial_ev100" { type = "number", default = o.initial_ev100 or post.ev100(aperture, shutter, iso, ec), min = -32, max = 32,
                               doc = "exposure of the first frame, before anything was metered" }
    rg.param "bloom_mix_stops" { type = "number", default = o.bloom_mix_stops or -6, min = -32, max = 0,
                                 doc = "the blurred image's share of the mix, in stops: (1 - w) image + w blur, w = 2^bloom_mix_stops" }
    rg.param "tonemap" { type = "choice", default = o.tonemap or "aces", choices = { "aces", "neutral", "linear" } }
    rg.param "dither" { type = "boolean", default = o.dither ~= false, doc = "triangular dither before 8-bit quantisation" }
    rg.param "fxaa_threshold" { type = "number", default = 0.125, min = 0, max = 1 }
    rg.param "fxaa_subpixel" { type = "number", default = 0.75, min = 0, max = 1 }
    post.antialiasing = o.antialiasing or "taa"  -- the default of the parameter post.chain declares with TAA
    post.declared = true
end

-- The persistent exposure state (shaders/lib/exposure.glsl, RgExposureState: 4 floats).
function post.exposure_state()
    rg.buffer "exposure" { size = 16, persistent = true }
end

-- TAA (shaders/post/taa.frag) on the pre-exposed HDR, first in the chain: `taa` blends the
-- frame into its history (`taa_history`, the `taa` image's history: rg.resource's `history`,
-- kept by the pass `taa_history_keep` while TAA reads it, emptied when the passes writing `taa`
-- change), reprojected by the camera's motion from `depth`. With another antialiasing, `taa_off`
-- copies the HDR through instead (post.frame switches them). Returns the image the chain goes on with.
local function temporal(input, depth, motion)
    rg.param "antialiasing" { type = "choice", default = post.antialiasing, choices = { "taa", "fxaa", "none" },
                              scene = "antialiasing",
                              doc = "taa: temporal, over jittered frames; fxaa: FXAA 3.11 on the display image; none" }
    rg.param "taa_jitter" { type = "boolean", default = true, scene = "jitter",
                            doc = "TAA's sub-pixel camera jitter (Halton 2, 3 over 8 frames); off in the golden tests' profile" }
    rg.param "taa_feedback" { type = "number", default = 0.9, min = 0, max = 0.99,
                              doc = "the history's share of a TAA pixel (before its luminance weighting)" }
    rg.resource "taa" { format = "rgba16f", history = "taa_history",
                        doc = "the HDR resolved over time: this frame blended into the reprojected history (`taa_history`: alpha 0 where empty)" }
    -- Two passes, one drawing on each frame (the fullscreen kind's `camera`): `taa` while the
    -- camera stands still (the history at the pixel itself), `taa_moving` when it moved (reprojected
    -- by the motion, read through a Catmull-Rom filter). Enabled as the parameter's default says,
    -- so that a pipeline that never calls post.frame still renders that choice.
    local on = post.antialiasing == "taa"
    rg.pass "taa" {
        kind = "fullscreen", shader = "post/taa.frag", camera = "still", enabled = on,
        reads = { input, "taa_history", { "exposure", as = "uniform" } }, writes = { "taa" },
        bind = { source = input },
    }
    local reads = { input, depth, "taa_history", { "exposure", as = "uniform" } }
    local bind = { source = input, depth = depth }
    if motion then  -- objects' motion (render_loop.lua's target, while the scene has moving nodes)
        table.insert(reads, motion)
        bind.motion = motion
    end
    rg.pass "taa_moving" {
        kind = "fullscreen", shader = "post/taa.frag", camera = "moved", filter = "linear", enabled = on,
        defines = { RG_TAA_MOVING = true, RG_MOTION = motion and true or nil },
        reads = reads, writes = { { "taa", load = true } }, bind = bind,
    }
    rg.pass "taa_off" { kind = "copy", reads = { input }, writes = { "taa" }, after = { "taa_moving" }, enabled = not on }
    post.taa = true
    return "taa"
end

-- Switches the passes of the `antialiasing` parameter (declared with TAA, by a chain given
-- `depth`): call it from rg.frame.
function post.frame(ctx)
    if not post.taa then return end
    local aa = ctx.params.antialiasing
    ctx.pass("taa").enabled = aa == "taa"
    ctx.pass("taa_moving").enabled = aa == "taa"
    ctx.pass("taa_off").enabled = aa ~= "taa"
    if post.fxaa then
        ctx.pass("fxaa_edges").enabled = aa == "fxaa"
        ctx.pass("fxaa").enabled = aa == "fxaa"
    end
end

-- o.input: the HDR target; o.output: the display image to create (rgba8, sRGB-encoded values);
-- o.depth: the depth buffer, for TAA (without it, or without post.params, no TAA);
-- o.bloom_levels (default 5, 0 = no bloom); o.fxaa (default true). Auto-exposure meters the
-- first bloom level (half size, the same average luminance: a quarter of the atomics) or the
-- input itself without bloom.
function post.chain(o)
    local input, output = assert(o.input, "post.chain: input"), assert(o.output, "post.chain: output")
    post.chained = true
    if o.depth and post.declared then input = temporal(input, o.depth, o.motion) end
    input = insert_passes("linear", input)
    local levels = o.bloom_levels or 5
    local meter = levels >= 1 and "bloom_down1" or input

    local previous = input
    for i = 1, levels do
        local name = "bloom_down" .. i
        rg.resource(name) { format = "rgba16f", scale = 0.5 ^ i }
        rg.pass(name) {
            kind = "fullscreen", shader = "post/bloom_down.frag", reads = { previous }, writes = { name }, bind = { source = previous },
            defines = i == 1 and { RG_BLOOM_BOX = true } or nil,
        }
        previous = name
    end

    rg.buffer "histogram" { size = 256 * 8 }
    rg.pass "exposure_clear" { kind = "clear", writes = { "histogram" } }
    rg.pass "exposure_histogram" {
        kind = "compute", shader = "post/histogram.comp", dispatch = meter,
        reads = { meter, { "exposure", as = "storage" } }, writes = { { "histogram", as = "storage_rw" } },
        bind = { hdr = meter },
    }
    rg.pass "exposure_update" {
        kind = "compute", shader = "post/exposure_update.comp", groups = { 1, 1, 1 },
        reads = { { "histogram", as = "storage" } }, writes = { { "exposure", as = "storage_rw" } },
    }
    local lower = "bloom_down" .. levels
    for i = levels - 1, 1, -1 do
        local name = "bloom_up" .. i
        rg.resource(name) { format = "rgba16f", scale = 0.5 ^ i }
        rg.pass(name) {
            kind = "fullscreen", shader = "post/bloom_up.frag", reads = { "bloom_down" .. i, lower }, writes = { name },
            bind = { down = "bloom_down" .. i, lower = lower },
        }
        lower = name
    end
    local reads = { input, { "exposure", as = "uniform" } }
    if levels >= 1 then table.insert(reads, 2, lower) end

    -- The tone mapping in stages (post/tonemap.frag's RG_POST_FROM/RG_POST_TO): 0 the HDR, 1
    -- exposed, 2 tone-mapped, 3 sRGB-encoded; a pass for each run of stages between used points.
    local fxaa = o.fxaa ~= false
    post.fxaa = fxaa
    local display = #post.inserted.display > 0 and (output .. "_chain") or output
    local mapped = fxaa and (output .. "_ldr") or display
    rg.resource(mapped) { format = "rgba8" }
    if fxaa then rg.resource(display) { format = "rgba8" } end
    local cuts = { 0 }
    if #post.inserted.exposed > 0 then table.insert(cuts, 1) end
    if #post.inserted.display_linear > 0 then table.insert(cuts, 2) end
    table.insert(cuts, 3)
    local source = input
    for k = 2, #cuts do
        local from, to = cuts[k - 1], cuts[k]
        local last = to == 3
        -- The pass that applies the curve is `tonemap`; one that ends before it `expose`, one
        -- after it `encode`.
        local name = to == 1 and "expose" or from == 2 and "encode" or "tonemap"
        local image = last and mapped or (to == 1 and "exposed" or "tonemapped")
        if not last then rg.resource(image) { format = "rgba16f" } end
        local switches = {}
        if post.declared and from <= 1 and to >= 2 then switches.tonemap = "RG_TONEMAP_CURVE" end
        if post.declared and last then switches.dither = "RG_DITHER" end
        local defines = { RG_POST_FROM = from, RG_POST_TO = to }
        if last and fxaa then defines.RG_TONEMAP_COPY = true end
        rg.pass(name) {
            kind = "fullscreen", shader = "post/tonemap.frag",
            reads = from == 0 and reads or { source },
            writes = (last and fxaa) and { mapped, display } or { image },
            defines = defines,
            bind = from == 0 and { hdr = input, bloom = levels >= 1 and lower or input } or { source = source },
            uniforms = from == 0 and { bloom_levels = levels } or nil,
            -- The curve and the dither compiled in when post.params declared them (a change rebuilds
            -- this pass only): the curves not chosen would run anyway on a CPU rasteriser.
            switches = next(switches) and switches or nil,
        }
        source = image
        if to == 1 then source = insert_passes("exposed", source) end
        if to == 2 then source = insert_passes("display_linear", source) end
    end
    if fxaa then
        -- FXAA on the blocks that have an edge only: `fxaa_edges` marks the pixels FXAA's contrast
        -- test would filter (depth 0; 1 elsewhere) and `fxaa` runs depth-tested over the tone
        -- mapping's copy in `output` — lavapipe's depth test drops the other blocks before
        -- shading them (a branch cannot), and they keep the copy, which is what FXAA writes for a
        -- pixel without an edge: the same image for ~6.5 ms (mask 3, filter 2.2, the copy 1.3) instead
        -- of ~12.5 at 1280x720.
        rg.resource "fxaa_edges" { format = "d16", doc = "FXAA's edge mask: depth 0 where its contrast test finds an edge" }
        -- (With TAA in the chain, on only when `antialiasing` says fxaa.)
        local fxaa_on = not post.taa or post.antialiasing == "fxaa"
        rg.pass "fxaa_edges" {
            kind = "fullscreen", shader = "post/fxaa_edges.frag", reads = { mapped }, writes = { { "fxaa_edges", as = "depth" } },
            enabled = fxaa_on,
            bind = { source = mapped }, depth = { compare = "always", value = 1, write = true },
        }
        rg.pass "fxaa" {
            kind = "fullscreen", shader = "post/fxaa.frag", reads = { mapped, { "fxaa_edges", as = "depth" } }, enabled = fxaa_on,
            writes = { { display, load = true } }, bind = { source = mapped }, depth = { compare = "greater", value = 1 },
        }
    end
    insert_passes("display", display, output)
end

return post
