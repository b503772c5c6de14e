#include "heightpack/bake/build/build_state.hpp"

#include <nlohmann/json.hpp>
#include <xxhash.h>

#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

#include "heightpack/io/read.hpp"

#include "build_common.hpp"

namespace heightpack {

namespace {

std::string hex128(XXH128_hash_t h) {
    char text[33];
    std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(h.high64),
                  static_cast<unsigned long long>(h.low64));
    return text;
}

}  // namespace

std::string hashText(const std::string& text) { return hex128(XXH3_128bits(text.data(), text.size())); }

Result<std::string> hashFile(const std::string& path) {
    if (Status s = checkReadable(path); !s) return s.error();  // a FIFO or device would hang the read
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!f) return badInput(path, "cannot be read", "check that it exists and is readable");
    std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state(XXH3_createState(), XXH3_freeState);
    XXH3_128bits_reset(state.get());
    std::vector<char> buffer(1 << 20);
    size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), f.get())) > 0) XXH3_128bits_update(state.get(), buffer.data(), n);
    if (std::ferror(f.get())) return badInput(path, "could not be read to the end", "check the disk");
    return hex128(XXH3_128bits_digest(state.get()));
}

BuildState parseBuildState(const std::string& text) {
    const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) return {};
    const auto format = doc.find("format");
    const auto outputs = doc.find("outputs");
    if (format == doc.end() || !format->is_number_integer() || *format != kBuildStateFormat || outputs == doc.end() ||
        !outputs->is_object())
        return {};
    BuildState state;
    for (const auto& [output, entry] : outputs->items()) {
        if (!entry.is_object()) return {};
        BuildStateEntry e;
        for (auto [key, field] : {std::pair{"key", &e.key}, std::pair{"hash", &e.hash}, std::pair{"checked", &e.checked}}) {
            const auto value = entry.find(key);
            if (value == entry.end() || !value->is_string()) return {};
            *field = value->get<std::string>();
        }
        state[output] = std::move(e);
    }
    return state;
}

BuildState readBuildState(const std::string& path) { return parseBuildState(detail::readText(path)); }

std::string buildStateText(const BuildState& state) {
    nlohmann::json outputs = nlohmann::json::object();
    for (const auto& [output, e] : state) outputs[output] = {{"key", e.key}, {"hash", e.hash}, {"checked", e.checked}};
    return nlohmann::json{{"format", kBuildStateFormat}, {"outputs", outputs}}.dump(1) + "\n";
}

}  // namespace heightpack
