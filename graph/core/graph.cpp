#include "graph.h"

namespace rg {

const char* usageName(Usage u) {
    switch (u) {
        case Usage::Sampled:
            return "Sampled";
        case Usage::UniformRead:
            return "UniformRead";
        case Usage::StorageRead:
            return "StorageRead";
        case Usage::StorageWrite:
            return "StorageWrite";
        case Usage::StorageReadWrite:
            return "StorageReadWrite";
        case Usage::ColorAttachment:
            return "ColorAttachment";
        case Usage::DepthStencilAttachment:
            return "DepthStencilAttachment";
        case Usage::DepthStencilRead:
            return "DepthStencilRead";
        case Usage::CopySrc:
            return "CopySrc";
        case Usage::CopyDst:
            return "CopyDst";
        case Usage::IndirectRead:
            return "IndirectRead";
    }
    return "?";
}

bool usageReads(Usage u, bool load) {
    switch (u) {
        case Usage::Sampled:
        case Usage::UniformRead:
        case Usage::StorageRead:
        case Usage::StorageReadWrite:
        case Usage::DepthStencilRead:
        case Usage::IndirectRead:
        case Usage::CopySrc:
            return true;
        // Attachments read what is there only when they keep it (load op LOAD, blending, depth test);
        // a copy destination that loads is a partial write (e.g. mips 1..n written from mip 0).
        case Usage::ColorAttachment:
        case Usage::DepthStencilAttachment:
        case Usage::CopyDst:
            return load;
        // A full overwrite: `load` has no meaning for it.
        case Usage::StorageWrite:
            return false;
    }
    return false;
}

bool usageWrites(Usage u) {
    switch (u) {
        case Usage::StorageWrite:
        case Usage::StorageReadWrite:
        case Usage::ColorAttachment:
        case Usage::DepthStencilAttachment:
        case Usage::CopyDst:
            return true;
        case Usage::Sampled:
        case Usage::UniformRead:
        case Usage::StorageRead:
        case Usage::DepthStencilRead:
        case Usage::IndirectRead:
        case Usage::CopySrc:
            return false;
    }
    return false;
}

const char* passTypeName(PassType t) {
    switch (t) {
        case PassType::Raster:
            return "raster";
        case PassType::Compute:
            return "compute";
        case PassType::Transfer:
            return "transfer";
    }
    return "?";
}

const ResourceDesc* GraphDesc::findResource(const std::string& name) const {
    for (const auto& r : resources)
        if (r.name == name) return &r;
    return nullptr;
}

const PassDesc* GraphDesc::findPass(const std::string& name) const {
    for (const auto& p : passes)
        if (p.name == name) return &p;
    return nullptr;
}

}  // namespace rg
