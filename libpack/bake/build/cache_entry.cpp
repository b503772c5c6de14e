#include "cache_entry.hpp"

#include <nlohmann/json.hpp>

#include "heightpack/bake/build/build_state.hpp"

namespace heightpack::detail {

namespace {
constexpr int kEntryFormat = 1;
constexpr const char* kEntryMark = "heightpack cache entry";
}  // namespace

std::string entryName(const std::string& key, const std::string& output) {
    const std::string name = hashText("key=" + key + "\noutput=" + std::to_string(output.size()) + ":" + output + "\n");
    return name.substr(0, 2) + "/" + name + ".bin";
}

std::string entryHeader(const std::string& key, const std::string& output, std::uint64_t size, const std::string& hash) {
    std::string header = nlohmann::json{{"entry", kEntryMark}, {"format", kEntryFormat}, {"key", key},
                                        {"output", output},    {"size", size},           {"hash", hash}}
                             .dump() +
                         "\n";
    if (header.size() > kEntryHeaderBytes) return {};
    header.resize(kEntryHeaderBytes, '\0');
    return header;
}

std::string judgeEntryHeader(const std::string& text, std::uint64_t entryBytes, const std::string& key,
                             const std::string& output, std::uint64_t& size, std::string& hash) {
    if (text.size() < kEntryHeaderBytes || entryBytes < kEntryHeaderBytes)
        return "it is shorter than an entry's header (truncated)";
    const nlohmann::json header = nlohmann::json::parse(text.substr(0, text.find('\n')), nullptr, false);
    auto field = [&](const char* name) {
        const auto it = header.is_object() ? header.find(name) : header.end();
        return it != header.end() && it->is_string() ? it->get<std::string>() : std::string("?");
    };
    if (!header.is_object() || field("entry") != kEntryMark || !header.contains("format") ||
        header["format"] != kEntryFormat || !header.contains("size") || !header["size"].is_number_unsigned())
        return "its header is not a heightpack cache entry's";
    if (field("key") != key || field("output") != output)
        return "it holds another output (" + field("output") + ", key " + field("key") + ")";
    size = header["size"].get<std::uint64_t>();
    hash = field("hash");
    if (entryBytes != kEntryHeaderBytes + size)
        return "it holds " + std::to_string(entryBytes - kEntryHeaderBytes) + " bytes where its header says " +
               std::to_string(size) + " (truncated or altered)";
    return {};
}

}  // namespace heightpack::detail
