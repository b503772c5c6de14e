// Damaged headers of heightpack's own textures, made by changing one value of one key in place (no length
// changes, so the file's structure stays sound and only the value is wrong): the family the readers must
// refuse as bad input, naming the file and the key. Header-only: the CLI and viewer tests share it.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "support/test_support.hpp"

namespace heightpack::test {

// One damage: in the file with extension ext, key's value becomes `text` (a text value: KTX2 key/values,
// EXR string attributes) or `number` (an EXR float attribute, a DDS record word).
struct HeaderDamage {
    std::string ext;   // ".exr", ".ktx2", ".dds"
    std::string key;   // "heightpack:layout", ...
    std::string text;  // same length as the value it replaces
    float number = 0.0f;
    std::uint32_t code = 0;  // a DDS record code word (layout, wrap), when not 0
    std::string name() const { return ext + " " + key + " = '" + (text.empty() ? (code ? std::to_string(code) : std::to_string(number)) : text) + "'"; }
};

// The family for files made by `pack seq.0000.exr --scale 0.25` from a synth sequence timed over 12 s:
// layout neighbour4, wrap periodic, filter kaiser, heightScale 0.25, loopPeriod 12.
inline std::vector<HeaderDamage> headerDamages() {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    std::vector<HeaderDamage> all;
    for (const char* ext : {".exr", ".ktx2"}) {
        for (const char* layout : {"neighbourX", "neighbour5", "plainplain"}) all.push_back({ext, "heightpack:layout", layout});
        for (const char* wrap : {"periodiX", "mirrored"}) all.push_back({ext, "heightpack:wrap", wrap});
        all.push_back({ext, "heightpack:filter", "kaiseX"});
    }
    for (const char* scale : {"xxxx", "-nan", "-inf", "0.2x"}) all.push_back({".ktx2", "heightpack:heightScale", scale});
    for (const char* period : {"-1", "00", "xx"}) all.push_back({".ktx2", "heightpack:loopPeriod", period});
    for (float scale : {nan, inf}) all.push_back({".exr", "heightpack:heightScale", "", scale});
    for (float period : {-1.0f, 0.0f, nan, inf}) all.push_back({".exr", "heightpack:loopPeriod", "", period});
    for (float scale : {nan, -inf}) all.push_back({".dds", "heightpack:heightScale", "", scale});
    for (float period : {-1.0f, 0.0f, nan}) all.push_back({".dds", "heightpack:loopPeriod", "", period});
    all.push_back({".dds", "heightpack:layout", "", 0.0f, 9});
    all.push_back({".dds", "heightpack:wrap", "", 0.0f, 7});
    return all;
}

// Applies damage to the file at path (made as headerDamages says); fails the test when the key is not there.
inline void damageHeader(const std::string& path, const HeaderDamage& damage) {
    std::vector<unsigned char> b = readBytes(path);
    const auto find = [&](const std::string& needle) {
        const auto at = std::search(b.begin(), b.end(), needle.begin(), needle.end());
        return at == b.end() ? std::string::npos : size_t(at - b.begin());
    };
    if (damage.ext == ".dds") {
        // The record's words (dds.cpp): layout 9, wrap 10, heightScale 11, loopPeriod 30, counted from the
        // header's start, after the 4-byte magic.
        const int word = damage.key == "heightpack:layout" ? 9 : damage.key == "heightpack:wrap" ? 10
                         : damage.key == "heightpack:heightScale" ? 11 : 30;
        std::uint32_t bits = damage.code;
        if (!bits) std::memcpy(&bits, &damage.number, 4);
        for (int k = 0; k < 4; ++k) b.at(4 + 4 * size_t(word) + size_t(k)) = (bits >> (8 * k)) & 0xff;
    } else if (!damage.text.empty()) {
        // KTX2: key NUL value NUL; EXR: name NUL "string" NUL size(4) value.
        const size_t key = find(damage.key + std::string(1, '\0'));
        ASSERT_NE(key, std::string::npos) << damage.name();
        size_t value = key + damage.key.size() + 1;
        if (damage.ext == ".exr") value += std::strlen("string") + 1 + 4;
        const size_t old = damage.ext == ".exr" ? le32(b, value - 4) : size_t(std::find(b.begin() + std::ptrdiff_t(value), b.end(), 0) - b.begin()) - value;
        ASSERT_EQ(old, damage.text.size()) << damage.name() << ": the new value must be as long as the old";
        std::memcpy(b.data() + value, damage.text.data(), damage.text.size());
    } else {
        // EXR: name NUL "float" NUL size(4) value(4).
        const size_t key = find(damage.key + std::string(1, '\0') + "float" + std::string(1, '\0'));
        ASSERT_NE(key, std::string::npos) << damage.name();
        std::memcpy(b.data() + key + damage.key.size() + 1 + 6 + 4, &damage.number, 4);
    }
    writeBytes(path, b);
}

// A copy of dir's good<ext> (the undamaged file of damage's container) named damaged<index><ext>, damaged.
inline std::string damagedCopy(const ScratchDir& dir, const HeaderDamage& damage, int index) {
    const std::string path = dir.file("damaged" + std::to_string(index) + damage.ext);
    std::filesystem::copy_file(dir.file("good" + damage.ext), path);
    damageHeader(path, damage);
    return path;
}

}  // namespace heightpack::test
