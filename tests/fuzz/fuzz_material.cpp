// readMaterial on arbitrary bytes as material.json, and, when the viewer is built, the viewer's own
// loading of it (applyMaterial: the numbers become its float settings). Any Error is fine. Findings: a
// crash, an uncaught exception, a sanitizer report (an out-of-range double to int or float is undefined
// behaviour), or a material that does not survive being written and read again unchanged.
#include <cstdint>

#include "fuzz_support.hpp"
#include "heightpack/bake/material.hpp"
#ifdef HEIGHTPACK_FUZZ_VIEWER
#include "material_settings.hpp"
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = heightpack::fuzz::writeInput("material.json", data, size);
    auto m = heightpack::readMaterial(path);
#ifdef HEIGHTPACK_FUZZ_VIEWER
    heightpack::view::SceneFiles files;
    heightpack::view::RenderSettings settings;
    std::string note;
    const heightpack::Status applied = heightpack::view::applyMaterial(path, files, settings, note);
    if (applied.ok() != (m.ok() && !m->displacement.empty())) __builtin_trap();
#endif
    if (!m) return 0;
    // What heightpack writes it reads back, to the same text.
    const std::string text = heightpack::materialJson(*m);
    const std::string again = heightpack::fuzz::writeInput("again.json", reinterpret_cast<const uint8_t*>(text.data()),
                                                           text.size());
    auto back = heightpack::readMaterial(again);
    if (!back || heightpack::materialJson(*back) != text) __builtin_trap();
    return 0;
}
