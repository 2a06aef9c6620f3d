// SceneBinding: a loaded scene as the executor sees it. The executor hands it to every pass kind
// (PassSetup::scene, RecordContext::scene) without knowing what a scene holds; the scene room
// above (passes::GpuScene) implements it, and its pass kinds read their own scene through it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rg::gpu {

class SceneBinding {
public:
    virtual ~SceneBinding() = default;

    // A number no other scene of the process has had (an address can be a freed scene's): a
    // build prepared against one scene is not reused for another.
    virtual uint64_t id() const = 0;
    // What the contents of frame `slot` are a function of (the once-cache's key).
    virtual uint64_t contentHash(uint32_t slot) const = 0;
    // The layers a texture declared with `scene_layers = NAME` gets from this scene (at most those
    // declared): nullopt when the scene has no extent NAME; 0 when it needs none, and the texture
    // then gets one 1×1 layer. extentNames() lists the names, for the error.
    virtual std::optional<uint32_t> layerExtent(const std::string& name) const = 0;
    virtual std::vector<std::string> extentNames() const = 0;
    // Whether the scene has feature NAME (a resource's `only_when.scene`): nullopt when the scene
    // knows no such feature; featureNames() lists them, for the error.
    virtual std::optional<bool> feature(const std::string& name) const = 0;
    virtual std::vector<std::string> featureNames() const = 0;
    // The features "material:NAME": whether a draw is of pipeline material NAME (the GPU scene's;
    // the session checks that NAME is a material of the pipeline).
    static constexpr std::string_view kMaterialFeature = "material:";
};

}  // namespace rg::gpu
