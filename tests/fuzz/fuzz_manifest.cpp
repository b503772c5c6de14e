// parseManifest on arbitrary bytes, as a material manifest beside a few real maps (map.png and a
// two-frame sequence seq.NNNN.png) so sources resolve and the parser goes past them. Any Error is fine;
// a crash, an assert (toml++'s included: this is built without NDEBUG), a sanitizer report or a
// manifest that breaks the parser's promises (outputs inside the output folder, unique) is a finding.
#include <cstdint>
#include <set>

#include "heightpack/bake/manifest.hpp"
#include "heightpack/io/files.hpp"

#include "fuzz_support.hpp"

namespace {

// A valid 1x1 8-bit grey PNG.
const uint8_t kPng[] = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
                        0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x00, 0x00, 0x00, 0x00, 0x3a,
                        0x7e, 0x9b, 0x55, 0x00, 0x00, 0x00, 0x0a, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x68,
                        0x00, 0x00, 0x00, 0x82, 0x00, 0x81, 0x77, 0xcd, 0x72, 0xb6, 0x00, 0x00, 0x00, 0x00, 0x49,
                        0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

void claim(std::set<std::string>& outputs, const std::string& output) {
    const std::filesystem::path p(output);
    if (output.empty() || p.is_absolute() || *p.begin() == ".." || !outputs.insert(output).second) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    using heightpack::fuzz::writeInput;
    for (const char* name : {"map.png", "seq.0000.png", "seq.0001.png"}) writeInput(name, kPng, sizeof kPng);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = heightpack::fuzz::writeInput("manifest.toml", data, size);
    auto m = heightpack::parseManifest(path);
    if (!m) return 0;
    std::set<std::string> outputs;
    for (const auto& d : m->displacement)
        for (size_t f = 0; f < d.frames.size(); ++f)
            claim(outputs, heightpack::frameFileName(d.output, int(f), int(d.frames.size())));
    if (m->normals) claim(outputs, m->normals->output);
    if (m->fresnel) claim(outputs, m->fresnel->output);
    if (m->foam && m->foam->texture) claim(outputs, m->foam->texture->output);
    return 0;
}
