// glTF materials -> Scene materials: samplers, images (decoded once per image and encoding),
// textures with KHR_texture_transform, the metallic-roughness factors and rgraph's extras.
#include <algorithm>
#include <cmath>
#include <optional>

#include <set>
#include <tuple>

#include "gltf_load_detail.h"
#include "scene_detail.h"
#include "tinygltf.h"

namespace rg {

using namespace scene_detail;

namespace gltf_load {

namespace {

// An extension's array of numbers as doubles, −1 for an entry that is not a number (the range
// checks then name it); empty when the value is not an array.
std::vector<double> numbers(const tinygltf::Value& v) {
    std::vector<double> out;
    for (int k = 0; v.IsArray() && k < int(v.ArrayLen()); ++k)
        out.push_back(v.Get(k).IsNumber() ? v.Get(k).GetNumberAsDouble() : -1.0);
    return out;
}

}  // namespace

void Loader::convertSamplers() {
    for (const auto& s : model.samplers) {
        SamplerDesc d;
        auto wrap = [](int w) {
            return w == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? Wrap::ClampToEdge
                   : w == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? Wrap::MirroredRepeat
                                                                : Wrap::Repeat;
        };
        d.wrapS = wrap(s.wrapS);
        d.wrapT = wrap(s.wrapT);
        d.magFilter =
            s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? Filter::Nearest : Filter::Linear;
        switch (s.minFilter) {
            case TINYGLTF_TEXTURE_FILTER_NEAREST:
            case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
                d.minFilter = Filter::Nearest;
                d.mipmapMode = MipmapMode::Nearest;
                break;
            case TINYGLTF_TEXTURE_FILTER_LINEAR:
            case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
                d.minFilter = Filter::Linear;
                d.mipmapMode = MipmapMode::Nearest;
                break;
            case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
                d.minFilter = Filter::Nearest;
                d.mipmapMode = MipmapMode::Linear;
                break;
            default:  // LINEAR_MIPMAP_LINEAR or undefined
                d.minFilter = Filter::Linear;
                d.mipmapMode = MipmapMode::Linear;
                break;
        }
        samplers.push_back(static_cast<int32_t>(scene.samplers.size()));
        scene.samplers.push_back(d);
    }
}

Result<int32_t> Loader::image(const std::string& where, int index, bool srgb) {
    if (auto it = images.find({index, srgb}); it != images.end()) return it->second;
    const auto& img = model.images[size_t(index)];
    const std::string label =
        named("image", size_t(index), !img.uri.empty() && !isDataUri(img.uri) ? img.uri : img.name);
    SceneImage out;
    out.name = !img.name.empty()                         ? img.name
               : !img.uri.empty() && !isDataUri(img.uri) ? img.uri
                                                         : "image " + std::to_string(index);
    out.srgb = srgb;
    if (options.loadImages) {
        if (auto e = imageState.errors.find(index); e != imageState.errors.end())
            return error(ErrorCode::InvalidInput, label + ": " + e->second);
        std::vector<unsigned char> bytes = img.image;
        if (bytes.empty() && !img.uri.empty() && !isDataUri(img.uri)) {
            auto inside = resolveInside(img.uri, label);
            if (!inside) return std::unexpected(inside.error());
            const std::string file = *inside;
            auto r = readFile(file);
            if (!r) return error(ErrorCode::InvalidInput, label + ": " + r.error().message);
            bytes = std::move(*r);
            addFile(file);
        }
        if (bytes.empty()) return error(ErrorCode::InvalidInput, label + ": no image data");
        auto decoded = decodeImage(bytes.data(), bytes.size());
        if (!decoded) return error(ErrorCode::InvalidInput, label + ": " + decoded.error().message);
        out.pixels = std::move(*decoded);
        if (options.generateMips) generateMips(out);
    }
    (void)where;
    const auto slot = static_cast<int32_t>(scene.images.size());
    scene.images.push_back(std::move(out));
    images[{index, srgb}] = slot;
    return slot;
}

glm::mat3 Loader::uvTransform(glm::vec2 offset, float rotation, glm::vec2 scale) {
    // KHR_texture_transform: T * R * S, rows of R = (cos, sin), (-sin, cos).
    const float c = std::cos(rotation), s = std::sin(rotation);
    const glm::mat3 t(glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(offset, 1));
    const glm::mat3 r(glm::vec3(c, -s, 0), glm::vec3(s, c, 0), glm::vec3(0, 0, 1));
    const glm::mat3 sc(glm::vec3(scale.x, 0, 0), glm::vec3(0, scale.y, 0), glm::vec3(0, 0, 1));
    return t * r * sc;
}

Result<TextureRef> Loader::texture(const std::string& where, int index, int texCoord,
                                   const tinygltf::ExtensionMap& ext, bool srgb) {
    TextureRef ref;
    if (index < 0) return ref;
    if (size_t(index) >= model.textures.size())
        return error(ErrorCode::InvalidInput,
                     where + ": texture " + std::to_string(index) + " does not exist (" +
                         std::to_string(model.textures.size()) + " textures)");
    const auto& tex = model.textures[size_t(index)];
    // KHR_texture_basisu (KTX2 / Basis Universal) has no Debian library: the texture's fallback
    // image (its plain `source`) is used, said once per texture; without one, the texture is left
    // out, said as well.
    const bool basisu = tex.extensions.count("KHR_texture_basisu") > 0;
    if (tex.source < 0) {
        warn(where + ": texture " + std::to_string(index) +
             (basisu ? " is KHR_texture_basisu only (KTX2, which rgraph cannot decode) and has no "
                       "PNG/JPEG fallback; ignored"
                     : " has no PNG/JPEG source; ignored"));
        return ref;
    }
    if (basisu && basisuWarned.insert(index).second)
        warn(where + ": texture " + std::to_string(index) +
             ": KHR_texture_basisu's KTX2 image cannot be decoded here; its fallback image " +
             std::to_string(tex.source) + " is used");
    if (size_t(tex.source) >= model.images.size())
        return error(ErrorCode::InvalidInput, where + ": texture " + std::to_string(index) +
                                                  " names image " + std::to_string(tex.source) +
                                                  ", which does not exist");
    if (tex.sampler >= 0 && size_t(tex.sampler) >= samplers.size())
        return error(ErrorCode::InvalidInput, where + ": texture " + std::to_string(index) +
                                                  " names sampler " + std::to_string(tex.sampler) +
                                                  ", which does not exist");
    auto img = image(where, tex.source, srgb);
    if (!img) return std::unexpected(img.error());
    ref.image = *img;
    ref.sampler = tex.sampler >= 0 ? samplers[size_t(tex.sampler)] : -1;
    int coord = texCoord;
    if (auto it = ext.find("KHR_texture_transform"); it != ext.end() && it->second.IsObject()) {
        const auto& t = it->second;
        glm::vec2 offset(0.0f), scale(1.0f);
        if (t.Has("offset") && t.Get("offset").IsArray() && t.Get("offset").ArrayLen() == 2)
            offset = glm::vec2(float(number(t.Get("offset").Get(0), 0)),
                               float(number(t.Get("offset").Get(1), 0)));
        if (t.Has("scale") && t.Get("scale").IsArray() && t.Get("scale").ArrayLen() == 2)
            scale = glm::vec2(float(number(t.Get("scale").Get(0), 1)),
                              float(number(t.Get("scale").Get(1), 1)));
        const float rotation = float(number(t.Get("rotation"), 0.0));
        ref.transform = uvTransform(offset, rotation, scale);
        if (t.Has("texCoord")) coord = indexOf(t.Get("texCoord"));
    }
    if (coord < 0 || coord > kMaxTexCoord) {
        warn(where + ": texCoord " + std::to_string(coord) + " is not a TEXCOORD_n (0.." +
             std::to_string(kMaxTexCoord) + "); using TEXCOORD_0");
        coord = 0;
    }
    // The glTF set for now: uvSlots() makes it one of the two a vertex carries.
    ref.texCoord = static_cast<uint32_t>(coord);
    return ref;
}

// A vertex carries two texture coordinate sets (uv0, uv1); a material's textures may name any
// TEXCOORD_n. Sets 0 and 1 stay in their own slots (TEXCOORD_1 is also the lightmap's); another
// set takes a slot the material's textures leave unused, and every primitive drawn with the
// material reads that set into it (primitive()). A third set has no slot: named in a warning, its
// textures read slot 0.
void Loader::uvSlots(const std::string& where, Material& m) {
    const std::vector<TextureRef*> refs = m.textureRefs();
    std::set<uint32_t> used;
    for (const TextureRef* r : refs)
        if (r->image >= 0) used.insert(r->texCoord);
    std::array<int, 2> slots = {0, 1};
    for (uint32_t set : used) {
        if (set <= 1) continue;
        // A slot still holding its own set (0 or 1), which the material does not use.
        int free = -1;
        for (int k = 0; k < 2 && free < 0; ++k)
            if (slots[size_t(k)] == k && !used.count(uint32_t(k))) free = k;
        if (free >= 0) {
            slots[size_t(free)] = int(set);
            continue;
        }
        warn(where +
             ": its textures name more than two texture coordinate sets; those on "
             "TEXCOORD_" +
             std::to_string(set) + " read TEXCOORD_" + std::to_string(slots[0]));
    }
    for (TextureRef* r : refs) {
        uint32_t slot = 0;
        for (uint32_t k = 0; k < 2; ++k)
            if (slots[k] == int(r->texCoord)) slot = k;
        r->texCoord = slot;
    }
    materialSlots.push_back(slots);
}

// A tinygltf JSON value -> Value (for material params written by exportGlb).
Value Loader::toValue(const tinygltf::Value& v) {
    if (v.IsBool()) return Value(v.Get<bool>());
    if (v.IsNumber()) return Value(v.GetNumberAsDouble());
    if (v.IsString()) return Value(v.Get<std::string>());
    if (v.IsArray()) {
        Value::List l;
        for (size_t i = 0; i < v.ArrayLen(); ++i) l.push_back(toValue(v.Get(int(i))));
        return Value(l);
    }
    if (v.IsObject()) {
        Value::Table t;
        for (const auto& k : v.Keys()) t[k] = toValue(v.Get(k));
        return Value(t);
    }
    return Value();
}

// The dielectric f0 of KHR_materials_ior (f0 = ((ior − 1)/(ior + 1))², 4 % at glTF's default
// 1.5) times KHR_materials_specular's specularFactor and the mean of its specularColorFactor, as
// the standard material's reflectance (f0 = 0.16 · reflectance², seed 000 tbl:2): a scalar, so a
// coloured specular keeps its mean (with a warning), and f0 is at most 16 % (ior ≈ 2.33).
Result<float> Loader::reflectanceOf(const tinygltf::Material& src, const std::string& where) {
    double ior = 1.5;
    if (auto it = src.extensions.find("KHR_materials_ior"); it != src.extensions.end())
        RG_TRY(ior, ranged(where + ": KHR_materials_ior.ior", number(it->second.Get("ior"), 1.5), 1,
                           1e3));
    double f0 = std::pow((ior - 1.0) / (ior + 1.0), 2.0);
    if (auto it = src.extensions.find("KHR_materials_specular"); it != src.extensions.end()) {
        const auto& x = it->second;
        double factor = 1.0;
        RG_TRY(factor, ranged(where + ": KHR_materials_specular.specularFactor",
                              number(x.Get("specularFactor"), 1.0), 0, 1));
        glm::vec3 colour(1.0f);
        if (x.Has("specularColorFactor")) {
            const auto& c = x.Get("specularColorFactor");
            for (int k = 0; k < 3 && c.IsArray() && c.ArrayLen() == 3; ++k)
                colour[k] = float(number(c.Get(k), 1.0));
            if (colour.x != colour.y || colour.y != colour.z)
                warn(where +
                     ": KHR_materials_specular.specularColorFactor is coloured; rgraph's "
                     "reflectance is one value, its mean is kept");
        }
        if (x.Has("specularTexture") || x.Has("specularColorTexture"))
            warn(where + ": KHR_materials_specular's textures are ignored (its factors are kept)");
        f0 *= factor * (colour.x + colour.y + colour.z) / 3.0;
    }
    if (f0 > 0.16)
        warn(where + ": f0 " + std::to_string(f0) + " is above the 16 % reflectance can hold");
    return float(std::sqrt(std::min(f0, 0.16) / 0.16));
}

// A textureInfo inside a material extension (KHR_materials_clearcoat's, specular-glossiness'):
// its index, texCoord and KHR_texture_transform, as texture() reads the core ones.
Result<TextureRef> Loader::extensionTexture(const std::string& where, const tinygltf::Value& info,
                                            bool srgb) {
    tinygltf::ExtensionMap ext;
    if (const auto& e = info.Get("extensions"); e.IsObject())
        for (const auto& key : e.Keys()) ext[key] = e.Get(key);
    return texture(where, indexOf(info.Get("index")),
                   info.Get("texCoord").IsNumber() ? indexOf(info.Get("texCoord")) : 0, ext, srgb);
}

// One model a material: whether the standard material may take the model of `extension` (else a
// warning says the extension is ignored). The models that take it keep f0 at 4 % in their
// layouts, so an IOR or specular extension that had changed the reflectance is named in a warning
// ("<keeps> f0 at 4 %") and the reflectance set back to 0.5.
bool Loader::takesModel(const std::string& where, const char* extension, const char* keeps,
                        Material& m) {
    if (m.model != "standard") {
        warn(where + ": " + extension + " is ignored: the material is already a '" + m.model +
             "' (one model a material)");
        return false;
    }
    if (std::abs(m.reflectance - 0.5f) > 1e-3f)
        warn(where + ": " + keeps + " f0 at 4 %; KHR_materials_ior/specular's reflectance " +
             std::to_string(m.reflectance) + " is dropped");
    m.reflectance = 0.5f;
    return true;
}

// KHR_materials_clearcoat on the standard model: the pipeline's clear_coat material
// (materials/clearcoat.lua) with coatStrength = clearcoatFactor, coatSmoothness =
// 1 − clearcoatRoughnessFactor and coatNormalScale = clearcoatNormalTexture.scale, its textures as
// the model's own: clearcoatTexture's R multiplies the strength (coatStrengthMap),
// clearcoatRoughnessTexture's G the roughness (coatRoughnessMap), clearcoatNormalTexture is the
// coat's normal (coatNormalMap; without it the coat takes the vertex normal, not the base's map).
// The clear coat layout keeps the base's f0 at 4 %: an IOR or specular extension that changed it is
// warned about.
Result<void> Loader::clearCoat(const tinygltf::Material& src, const std::string& where,
                               Material& m) {
    auto it = src.extensions.find("KHR_materials_clearcoat");
    if (it == src.extensions.end()) return {};
    const auto& x = it->second;
    const std::string ext = where + ": KHR_materials_clearcoat.";
    double factor = 0.0, roughness = 0.0, normalScale = 1.0;
    RG_TRY(factor, ranged(ext + "clearcoatFactor", number(x.Get("clearcoatFactor"), 0.0), 0, 1));
    RG_TRY(roughness, ranged(ext + "clearcoatRoughnessFactor",
                             number(x.Get("clearcoatRoughnessFactor"), 0.0), 0, 1));
    if (x.Get("clearcoatNormalTexture").IsObject())
        RG_TRY(normalScale,
               ranged(ext + "clearcoatNormalTexture.scale",
                      number(x.Get("clearcoatNormalTexture").Get("scale"), 1.0), -1e6, 1e6));
    if (factor <= 0.0 || !takesModel(where, "KHR_materials_clearcoat",
                                     "the clear coat material keeps the base's", m))
        return {};
    for (const auto& [field, name] : {std::pair{"clearcoatTexture", "coatStrengthMap"},
                                      std::pair{"clearcoatRoughnessTexture", "coatRoughnessMap"},
                                      std::pair{"clearcoatNormalTexture", "coatNormalMap"}})
        if (x.Get(field).IsObject()) {
            RG_TRY(m.textures[name], extensionTexture(where + " KHR_materials_clearcoat." + field,
                                                      x.Get(field), false));
        }
    m.model = "clear_coat";
    m.extra = Value(Value::Table{{"coatStrength", Value(factor)},
                                 {"coatSmoothness", Value(1.0 - roughness)},
                                 {"coatNormalScale", Value(normalScale)}});
    return {};
}

// KHR_materials_sheen on the standard model: the pipeline's sheen material (materials/sheen.lua)
// with sheenColorR/G/B = sheenColorFactor and sheenRoughnessFactor, its textures as the model's
// own: sheenColorTexture (RGB, sRGB) times the colour (sheenColorMap), sheenRoughnessTexture's
// alpha times the roughness (sheenRoughnessMap). A black sheen (the default) is no sheen. One
// model a material: beside a clear coat the sheen is dropped with a warning; the sheen layout
// keeps f0 at 4 %, so an IOR or specular extension that changed it is warned about too.
Result<void> Loader::sheen(const tinygltf::Material& src, const std::string& where, Material& m) {
    auto it = src.extensions.find("KHR_materials_sheen");
    if (it == src.extensions.end()) return {};
    const auto& x = it->second;
    const std::string ext = where + ": KHR_materials_sheen.";
    glm::vec3 colour(0.0f);
    RG_TRY(colour, ranged3(ext + "sheenColorFactor", numbers(x.Get("sheenColorFactor")),
                           glm::vec3(0.0f), 0, 1));
    double roughness = 0.0;
    RG_TRY(roughness,
           ranged(ext + "sheenRoughnessFactor", number(x.Get("sheenRoughnessFactor"), 0.0), 0, 1));
    if (std::max({colour.x, colour.y, colour.z}) <= 0.0f ||
        !takesModel(where, "KHR_materials_sheen", "the sheen material keeps", m))
        return {};
    for (const auto& [field, name, srgb] :
         {std::tuple{"sheenColorTexture", "sheenColorMap", true},
          std::tuple{"sheenRoughnessTexture", "sheenRoughnessMap", false}})
        if (x.Get(field).IsObject()) {
            RG_TRY(m.textures[name],
                   extensionTexture(where + " KHR_materials_sheen." + field, x.Get(field), srgb));
        }
    m.model = "sheen";
    m.extra = Value(Value::Table{{"sheenColorR", Value(double(colour.x))},
                                 {"sheenColorG", Value(double(colour.y))},
                                 {"sheenColorB", Value(double(colour.z))},
                                 {"sheenRoughnessFactor", Value(roughness)}});
    return {};
}

// KHR_materials_transmission (with KHR_materials_volume) on the standard model: the pipeline's
// transmission material (materials/transmission.lua), drawn by the forward pass over the opaque
// frame it refracts — so the material becomes blended, whatever its alphaMode —
// transmissionFactor and thicknessFactor, attenuationDistance (absent: 0, none) and
// attenuationColor as its params, transmissionTexture (R) and thicknessTexture (G) as its own
// textures. The IOR stays the reflectance (reflectanceOf). A factor of 0 is no transmission. The volume's thickness is put in the world's units by volumeScale.
Result<void> Loader::transmission(const tinygltf::Material& src, const std::string& where,
                                  Material& m) {
    auto it = src.extensions.find("KHR_materials_transmission");
    auto volume = src.extensions.find("KHR_materials_volume");
    if (it == src.extensions.end()) {
        if (volume != src.extensions.end())
            warn(where +
                 ": KHR_materials_volume is ignored without KHR_materials_transmission "
                 "(a volume is seen only through a transmitting surface)");
        return {};
    }
    const auto& x = it->second;
    const std::string ext = where + ": KHR_materials_transmission.";
    double factor = 0.0;
    RG_TRY(factor,
           ranged(ext + "transmissionFactor", number(x.Get("transmissionFactor"), 0.0), 0, 1));
    if (factor <= 0.0) return {};  // glTF's transmission is the factor times the texture's R
    if (x.Get("transmissionTexture").IsObject())
        RG_TRY(m.textures["transmissionMap"],
               extensionTexture(ext + "transmissionTexture", x.Get("transmissionTexture"), false));
    double thickness = 0.0, distance = 0.0;
    glm::vec3 colour(1.0f);
    if (volume != src.extensions.end()) {
        const auto& v = volume->second;
        const std::string vol = where + ": KHR_materials_volume.";
        RG_TRY(thickness,
               ranged(vol + "thicknessFactor", number(v.Get("thicknessFactor"), 0.0), 0, HUGE_VAL));
        if (v.Has("attenuationDistance"))
            RG_TRY(distance, ranged(vol + "attenuationDistance",
                                    number(v.Get("attenuationDistance"), 0.0), 1e-9, HUGE_VAL));
        RG_TRY(colour, ranged3(vol + "attenuationColor", numbers(v.Get("attenuationColor")),
                               glm::vec3(1.0f), 0, 1));
        if (v.Get("thicknessTexture").IsObject())
            RG_TRY(m.textures["thicknessMap"],
                   extensionTexture(vol + "thicknessTexture", v.Get("thicknessTexture"), false));
    }
    m.model = "transmission";
    m.extra = Value(Value::Table{{"transmissionFactor", Value(factor)},
                                 {"thicknessFactor", Value(thickness)},
                                 {"attenuationDistance", Value(distance)},
                                 {"attenuationColorR", Value(double(colour.x))},
                                 {"attenuationColorG", Value(double(colour.y))},
                                 {"attenuationColorB", Value(double(colour.z))}});
    return {};
}

// KHR_materials_pbrSpecularGlossiness onto the two-colour base material (seed 000 tbl:3), which
// holds exactly its two colours: diffuseFactor (× diffuseTexture, sRGB, as the base colour
// texture; its alpha the opacity) as the diffuse colour, specularFactor as the f0 colour and
// glossinessFactor as the smoothness; specularGlossinessTexture (RGB sRGB, A linear) is the
// model's own texture specularGlossinessMap, multiplying f0 and smoothness
// (materials/two_colour.glsl).
Result<void> Loader::specularGlossiness(const tinygltf::Material& src, const std::string& where,
                                        Material& m) {
    auto it = src.extensions.find("KHR_materials_pbrSpecularGlossiness");
    if (it == src.extensions.end()) return {};
    const auto& x = it->second;
    const std::string ext = where + ": KHR_materials_pbrSpecularGlossiness.";
    std::vector<double> diffuse = numbers(x.Get("diffuseFactor"));
    double alpha = 1.0;
    if (diffuse.size() == 4) {
        RG_TRY(alpha, ranged(ext + "diffuseFactor[3]", diffuse[3], 0, 1));
        diffuse.pop_back();
    }
    RG_TRY(m.diffuseColor, ranged3(ext + "diffuseFactor", diffuse, glm::vec3(1.0f), 0, 1));
    RG_TRY(m.f0, ranged3(ext + "specularFactor", numbers(x.Get("specularFactor")), glm::vec3(1.0f),
                         0, 1));
    double glossiness = 1.0;
    RG_TRY(glossiness,
           ranged(ext + "glossinessFactor", number(x.Get("glossinessFactor"), 1.0), 0, 1));
    if (m.model != "standard")
        warn(where +
             ": KHR_materials_pbrSpecularGlossiness makes it the two-colour material; its '" +
             m.model + "' extension is dropped (one model a material)");
    m.model = "two_colour";
    m.extra = Value();
    m.textures.clear();
    m.baseColor = m.diffuseColor;  // what debug views and decals call it (its channels map)
    m.opacity = float(alpha);
    m.smoothness = float(glossiness);
    m.metalMask = 0.0f;
    m.metallicRoughnessTex = TextureRef{};  // the metallic-roughness model's: not this one's
    if (x.Get("diffuseTexture").IsObject())
        RG_TRY(m.baseColorTex,
               extensionTexture(where + " diffuseTexture", x.Get("diffuseTexture"), true));
    if (x.Get("specularGlossinessTexture").IsObject())
        RG_TRY(m.textures["specularGlossinessMap"],
               extensionTexture(where + " specularGlossinessTexture",
                                x.Get("specularGlossinessTexture"), true));
    return {};
}

Result<void> Loader::materials() {
    for (size_t i = 0; i < model.materials.size(); ++i) {
        const auto& src = model.materials[i];
        const std::string where = named("material", i, src.name);
        Material m;
        m.name = src.name.empty() ? "material " + std::to_string(i) : src.name;
        const auto& pbr = src.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() != 4)
            return error(ErrorCode::InvalidInput, where + ": baseColorFactor has " +
                                                      std::to_string(pbr.baseColorFactor.size()) +
                                                      " values, expected 4");
        glm::vec4 base;
        for (int k = 0; k < 4; ++k) {
            auto r = ranged(where + ": baseColorFactor[" + std::to_string(k) + "]",
                            pbr.baseColorFactor[size_t(k)], 0, 1);
            if (!r) return std::unexpected(r.error());
            base[k] = *r;
        }
        m.baseColor = glm::vec3(base);
        m.opacity = base.a;
        float roughness = 1.0f, strength = 1.0f;
        RG_TRY(m.metalMask, ranged(where + ": metallicFactor", pbr.metallicFactor, 0, 1));
        RG_TRY(roughness, ranged(where + ": roughnessFactor", pbr.roughnessFactor, 0, 1));
        m.smoothness = 1.0f - roughness;  // glTF roughness is perceptual (DESIGN.md §5)
        RG_TRY(m.reflectance, reflectanceOf(src, where));
        // One model a material: a transmission first (it decides whether anything is seen
        // behind the surface), then a coat or a sheen.
        if (auto r = transmission(src, where, m); !r) return r;
        if (auto r = clearCoat(src, where, m); !r) return r;
        if (auto r = sheen(src, where, m); !r) return r;
        if (auto it = src.extensions.find("KHR_materials_emissive_strength");
            it != src.extensions.end())
            RG_TRY(strength, ranged(where + ": emissiveStrength",
                                    number(it->second.Get("emissiveStrength"), 1.0), 0, HUGE_VAL));
        glm::vec3 emissive;
        RG_TRY(emissive,
               ranged3(where + ": emissiveFactor", src.emissiveFactor, glm::vec3(0.0f), 0, 1));
        // Read relative to the exposure, a factor of 1 white (see kGltfEmissiveEc).
        m.emissive = emissive * strength;
        m.emissiveEv = true;
        m.emissiveEc = kGltfEmissiveEc;
        auto tex = [&](const char* what, int index, int texCoord, const tinygltf::ExtensionMap& ext,
                       bool srgb, TextureRef& out) -> Result<void> {
            auto r = texture(where + " " + what, index, texCoord, ext, srgb);
            if (!r) return std::unexpected(r.error());
            out = *r;
            return {};
        };
        if (auto r =
                tex("baseColorTexture", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                    pbr.baseColorTexture.extensions, true, m.baseColorTex);
            !r)
            return r;
        if (auto r = tex("metallicRoughnessTexture", pbr.metallicRoughnessTexture.index,
                         pbr.metallicRoughnessTexture.texCoord,
                         pbr.metallicRoughnessTexture.extensions, false, m.metallicRoughnessTex);
            !r)
            return r;
        if (auto r = tex("normalTexture", src.normalTexture.index, src.normalTexture.texCoord,
                         src.normalTexture.extensions, false, m.normalTex);
            !r)
            return r;
        if (auto r =
                tex("occlusionTexture", src.occlusionTexture.index, src.occlusionTexture.texCoord,
                    src.occlusionTexture.extensions, false, m.occlusionTex);
            !r)
            return r;
        if (auto r = tex("emissiveTexture", src.emissiveTexture.index, src.emissiveTexture.texCoord,
                         src.emissiveTexture.extensions, true, m.emissiveTex);
            !r)
            return r;
        RG_TRY(m.normalScale,
               ranged(where + ": normalTexture.scale", src.normalTexture.scale, -1e6, 1e6));
        RG_TRY(m.occlusionStrength,
               ranged(where + ": occlusionTexture.strength", src.occlusionTexture.strength, 0, 1));
        // KHR_materials_unlit: the base colour shown as it is, whatever the light — emission
        // relative to the exposure as glTF's emissive is read (a factor of 1 white before the
        // tone curve), over a surface that reflects nothing (black, no metal, no specular). The
        // base colour texture still gives the opacity.
        if (src.extensions.count("KHR_materials_unlit")) {
            m.emissive = m.baseColor;
            m.emissiveTex = m.baseColorTex;
            m.emissiveEv = true;
            m.emissiveEc = kGltfEmissiveEc;
            m.baseColor = glm::vec3(0.0f);
            m.metalMask = 0.0f;
            m.reflectance = 0.0f;
            m.metallicRoughnessTex = m.normalTex = m.occlusionTex = TextureRef{};
            // Nothing reflects: no coat, no sheen either.
            m.model = "standard";
            m.extra = Value();
            m.textures.clear();
        }
        if (src.alphaMode == "OPAQUE" || src.alphaMode.empty())
            m.alphaMode = AlphaMode::Opaque;
        else if (src.alphaMode == "MASK")
            m.alphaMode = AlphaMode::Mask;
        else if (src.alphaMode == "BLEND")
            m.alphaMode = AlphaMode::Blend;
        else
            return error(ErrorCode::InvalidInput, where + ": alphaMode '" + src.alphaMode +
                                                      "', expected OPAQUE, MASK or BLEND");
        RG_TRY(m.alphaCutoff, ranged(where + ": alphaCutoff", src.alphaCutoff, 0, HUGE_VAL));
        m.doubleSided = src.doubleSided;
        if (auto r = specularGlossiness(src, where, m); !r) return r;
        // What glTF cannot say, as exportGlb wrote it; its own textures before uvSlots() places
        // every texture's set.
        const bool exported = src.extras.IsObject() && src.extras.Has("rgraph") &&
                              src.extras.Get("rgraph").IsObject();
        if (exported) {
            const auto& x = src.extras.Get("rgraph");
            if (x.Get("model").IsString()) m.model = x.Get("model").Get<std::string>();
            m.reflectance = float(number(x.Get("reflectance"), m.reflectance));
            m.ao = float(number(x.Get("ao"), m.ao));
            m.diffuseColor = vec3Of(x.Get("diffuse_color"), m.diffuseColor);
            m.f0 = vec3Of(x.Get("f0"), m.f0);
            if (x.Get("emissive_unit").IsString()) {
                m.emissiveEv = x.Get("emissive_unit").Get<std::string>() == "ev";
                m.emissiveEc = m.emissiveEv ? float(number(x.Get("emissive_ec"), 0.0)) : 0.0f;
            }
            if (x.Has("params")) m.extra = toValue(x.Get("params"));
            const auto& own = x.Get("textures");  // the model's own, as textureInfo by name
            for (const auto& name : own.IsObject() ? own.Keys() : std::vector<std::string>{}) {
                const auto& info = own.Get(name);
                if (!info.IsObject()) continue;
                const bool srgb = info.Get("srgb").IsBool() && info.Get("srgb").Get<bool>();
                RG_TRY(m.textures[name],
                       extensionTexture(where + " extras.rgraph.textures." + name, info, srgb));
            }
        }
        // A transmission (the final model, after specular-glossiness and exportGlb's extras) is
        // drawn by the forward pass only, over the opaque frame it refracts.
        if (m.model == "transmission" && m.alphaMode != AlphaMode::Blend) {
            if (m.alphaMode == AlphaMode::Mask)
                warn(where +
                     ": alphaMode MASK on a transmission is drawn blended (the forward "
                     "pass draws transmission), its cut-off not applied");
            m.alphaMode = AlphaMode::Blend;
        }
        uvSlots(where, m);
        // A volume's thickness is in its mesh's space (volumeScale puts it in the world's), unless
        // exportGlb wrote it, already in the world's.
        if (m.model == "transmission" && !exported && m.extra["thicknessFactor"].asNumber() > 0.0)
            volumes.push_back(scene.materials.size());
        scene.materials.push_back(std::move(m));
    }
    return {};
}

// KHR_materials_volume gives the thickness in the coordinate space of the mesh: each volume's
// thicknessFactor times the scale of the nodes that draw it (the mean length of their world
// transform's axes; the glTF sample viewer scales the refracted ray per axis, the same for a uniform
// scale). Skinned nodes (posed in the world) keep it as given. A material is one set of parameters:
// nodes of other scales take the first one's, with a warning.
void Loader::volumeScale() {
    for (size_t mi : volumes) {
        std::optional<float> scale;
        bool differ = false;
        for (const Node& n : scene.nodes) {
            if (n.mesh < 0 || static_cast<size_t>(n.mesh) >= scene.meshes.size()) continue;
            const auto& prims = scene.meshes[static_cast<size_t>(n.mesh)].primitives;
            if (std::none_of(prims.begin(), prims.end(),
                             [&](const Primitive& p) { return p.material == mi; }))
                continue;
            const float s =
                (glm::length(glm::vec3(n.world[0])) + glm::length(glm::vec3(n.world[1])) +
                 glm::length(glm::vec3(n.world[2]))) /
                3.0f;
            if (!scale) scale = s;
            differ = differ || std::abs(s - *scale) > 0.01f * *scale;
        }
        if (!scale) continue;
        Material& m = scene.materials[mi];
        m.extra.table()["thicknessFactor"] = Value(m.extra["thicknessFactor"].asNumber() * *scale);
        if (differ)
            warn("material '" + m.name +
                 "': KHR_materials_volume's thickness is scaled by its first "
                 "node's scale " +
                 std::to_string(*scale) +
                 "; nodes of other scales draw it with "
                 "that thickness too");
    }
}

}  // namespace gltf_load

}  // namespace rg
