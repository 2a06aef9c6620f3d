-- The standard debug views of `--view NAME` (rgraph render, serve and watch; SessionOptions::view
-- in the library). Each is an rg.view whose function, called when its view is asked for, declares
-- the passes that draw it into `debug_view` (rgba8, display-ready) after the pipeline's own. The
-- runtime loads this file when a view is asked for that the pipeline's scripts do not declare; a
-- pipeline adds views of its own with rg.view (scripts/README.md, "rg.view").
--
--   local views = require "views"
--   rg.view "albedo_x2" { doc = "...", build = function(v)
--       views.need(v, "GB1", "the G-buffer's base colour")
--       views.fullscreen { shader = "my/albedo_view.frag", reads = { "GB1" } }
--   end }
local rg = require "rg"

local views = {}

-- The image every view writes (SessionOptions::view: what `render` shows instead of the display).
function views.target()
    rg.resource "debug_view" { format = "rgba8" }
end

-- Stops the view with "--view NAME: the pipeline has no 'RESOURCE' (hint)" unless it has it.
function views.need(v, resource, hint)
    if type(resource) == "table" then resource = resource[1] end  -- { "depth", as = "stencil" }
    if not v.resources[resource] then
        v.fail("the pipeline has no '" .. resource .. "' (" .. hint .. ")")
    end
end

-- One fullscreen pass into debug_view: { shader, reads, uniforms, defines, bind }.
function views.fullscreen(p)
    views.target()
    rg.pass "debug_view" {
        kind = "fullscreen", shader = p.shader, reads = p.reads, writes = { "debug_view" },
        uniforms = p.uniforms, defines = p.defines, bind = p.bind,
    }
end

-- The G-buffer views: every pixel decoded with its own material's layout (gbuffer_pipeline.glsl)
-- and the standard parameter shown; a parameter the pixel's layout lacks shows as magenta
-- stripes (shaders/passes/debug_view.frag, whose `view` uniform picks it).
local gbuffer = { "GB0", "GB1", "GB2", "GB3", "depth", { "depth", as = "stencil" } }
local function gbuffer_view(v, index)
    for _, r in ipairs(gbuffer) do
        views.need(v, r, "views read the G-buffer GB0..GB3 and depth")
    end
    views.fullscreen { shader = "passes/debug_view.frag", reads = gbuffer, uniforms = { view = index } }
end
local channels = {
    { "normals", "the world normal, n * 0.5 + 0.5" },
    { "basecolor", "the base colour" },
    { "smoothness", "the smoothness, grey" },
    { "metalmask", "the metal mask, grey" },
    { "materialid", "the material identity (its stencil value), one colour each" },
    { "reflectance", "the reflectance, grey" },
    { "ao", "the baked ambient occlusion, grey" },
    { "emissive", "the emission (or the lightmap's radiosity), x / (1 + x) of nits / 300" },
}
for i, c in ipairs(channels) do
    local index = i - 1
    rg.view(c[1]) { doc = c[2], build = function(v) gbuffer_view(v, index) end }
end

-- One colour per stencil class, each drawn with its class's stencil test over black.
local palette = {
    { 0.9, 0.2, 0.2 }, { 0.2, 0.8, 0.2 }, { 0.2, 0.4, 0.9 }, { 0.9, 0.8, 0.2 },
    { 0.8, 0.3, 0.9 }, { 0.2, 0.9, 0.9 }, { 0.9, 0.5, 0.1 }, { 0.6, 0.6, 0.6 },
}
rg.view "stencil" { doc = "each stencil class in a colour of its own (in declaration order)", build = function(v)
    views.need(v, "depth", "the stencil is depth's")
    views.target()
    rg.pass "debug_view_clear" { kind = "clear", writes = { "debug_view" }, value = { 0, 0, 0, 1 } }
    for i, c in ipairs(v.stencil_classes) do
        local rgb = palette[(i - 1) % #palette + 1]
        rg.pass("debug_view_" .. c.name:gsub("%.", "_")) {
            kind = "fullscreen", shader = "passes/stencil_view.frag",
            reads = { { "depth", as = "depth" } }, writes = { { "debug_view", load = true } },
            stencil = { ref = c.value, mask = 255, compare = "equal" },
            uniforms = { class_color = { rgb[1], rgb[2], rgb[3], 1 } },
        }
    end
end }

rg.view "lights" { doc = "the lights of each screen tile, counted", build = function(v)
    views.need(v, "light_tiles", "require \"lighting\" and light its passes with lighting.tiled")
    views.fullscreen {
        shader = "passes/light_count_view.frag", reads = { { "light_tiles", as = "storage" }, "depth" },
        defines = { RG_LIGHT_TILES = true },
    }
end }

-- The reflections, in nits through the frame's exposure (shaders/passes/ssr_view.frag).
local function reflection_view(source, hint, mode)
    return function(v)
        views.need(v, source, hint)
        views.need(v, "exposure", "post.exposure_state(): the reflection is in nits")
        views.fullscreen {
            shader = "passes/ssr_view.frag", reads = { source, { "exposure", as = "storage" } },
            bind = source ~= "ssr" and { ssr = source } or nil, uniforms = { view = mode },
        }
    end
end
rg.view "ssr" { doc = "the screen-space reflection times its confidence", build = reflection_view("ssr", "require \"ssr\"", 0) }
rg.view "ssr_confidence" { doc = "the screen-space reflection's confidence", build = reflection_view("ssr", "require \"ssr\"", 1) }
rg.view "reflection" { doc = "SSR and the probes composed", build = reflection_view("reflection", "require \"reflections\"", 2) }

rg.view "probes" { doc = "which local light probe reflects each pixel (palette colour k for the k-th)", build = function(v)
    views.need(v, "depth", "the probes are found by each pixel's position")
    views.fullscreen { shader = "passes/probe_view.frag", reads = { "depth" } }
end }

rg.view "motion" { doc = "each pixel's screen motion since the last frame, as TAA reprojects by it: hue the direction, brightness the length (full at 8 pixels)", build = function(v)
    views.need(v, "depth", "the motion is the camera's, found from each pixel's depth")
    -- The motion target the scene passes write (require "motion"), the objects' own motion where
    -- they were drawn: while nodes move (otherwise the target and RG_MOTION leave the graph).
    views.fullscreen(require("motion").reads { shader = "passes/motion_view.frag", reads = { "depth" } })
end }

rg.view "ssao" { doc = "the screen-space ambient occlusion", build = function(v)
    views.need(v, "ssao", "require \"ao\"")
    views.fullscreen { shader = "passes/ssao_view.frag", reads = { "ssao" } }
end }

-- The sun's cascades: their maps side by side (shadow), or which cascade shades each pixel.
local function sun_view(cascades_on_screen)
    return function(v)
        for _, r in ipairs { "sun_shadow0", "sun_cascades" } do views.need(v, r, "require \"shadows\"") end
        local maps = {}
        while #maps < 4 and v.resources["sun_shadow" .. #maps] do maps[#maps + 1] = "sun_shadow" .. #maps end
        local defines = { RG_SUN_CASCADES = #maps }
        if not cascades_on_screen then
            views.fullscreen { shader = "passes/shadow_map_view.frag", reads = maps, defines = defines }
            return
        end
        local reads = require("gbuffer_reader").reads { "depth", { "sun_cascades", as = "uniform" } }
        for _, m in ipairs(maps) do reads[#reads + 1] = m end
        views.fullscreen { shader = "passes/cascade_view.frag", reads = reads, defines = defines }
    end
end
rg.view "cascades" { doc = "the sun's shadow cascade of each pixel", build = sun_view(true) }
rg.view "shadow" { doc = "the sun's shadow maps, one per cascade", build = sun_view(false) }

rg.view "shadow:LIGHT" {
    doc = "a local light's shadow maps this frame (a spot's one; a cube's six in a 3 x 2 grid)",
    pattern = "^shadow:(.+)$",
    build = function(v, name)
        views.need(v, "local_shadow", "require \"shadows\"")
        local index, shadowed = nil, {}
        for i, l in ipairs(v.scene and v.scene.lights or {}) do
            if l.shadow then
                shadowed[#shadowed + 1] = "'" .. l.name .. "'"
                if l.name == name then index = i - 1 end
            end
        end
        if not index then
            v.fail("the scene has no light '" .. name .. "' that casts shadows (" ..
                (#shadowed == 0 and "none does: give a local light shadow = true"
                    or "those that do: " .. table.concat(shadowed, ", ")) .. ")")
        end
        views.fullscreen { shader = "passes/local_shadow_view.frag", reads = { "local_shadow" }, uniforms = { light = index } }
    end,
}

-- The baked lightmap: the G-buffer pass writes it as the emission (RG_LIGHTMAP_VIEW: 1 the
-- irradiance at the shaded normal, 2 + N lobe N's amplitude), shown in colour.
local function lightmap_view(v, what)
    v.define("gbuffer", "RG_LIGHTMAP_VIEW", what + 1)
    for _, r in ipairs(gbuffer) do views.need(v, r, "views read the G-buffer GB0..GB3 and depth") end
    views.fullscreen { shader = "passes/debug_view.frag", reads = gbuffer, uniforms = { view = 8 } }
end
local function lightmap_of(v)
    local lm = v.scene and v.scene.lightmap
    if not lm then
        v.fail("the scene has no baked lightmap (declare scene.lightmap; the pipeline's lightmap parameter must be on)")
    end
    return lm
end
rg.view "lightmap" { doc = "the baked lightmap's irradiance at each pixel's normal", build = function(v)
    lightmap_of(v)
    lightmap_view(v, 0)
end }
rg.view "sgN" { doc = "the baked lightmap's lobe N", pattern = "^sg(%d+)$", build = function(v, n)
    local lobes, lobe = lightmap_of(v).lobes, tonumber(n)
    if lobe >= lobes then v.fail("the lightmap has lobes sg0 .. sg" .. (lobes - 1)) end
    lightmap_view(v, lobe + 1)
end }

return views
