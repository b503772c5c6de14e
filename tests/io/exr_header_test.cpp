// The OpenEXR header judged as OpenEXR 3.1 reads it (issue 34): every attribute type OpenEXR writes loads,
// and an attribute whose reader would stop elsewhere than its size says is refused before OpenEXR reads
// the rest of the header out of step (how a 2 KB file made it allocate a 2 GB string).
#include <OpenEXR/ImfBoxAttribute.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfChromaticitiesAttribute.h>
#include <OpenEXR/ImfDeepImageStateAttribute.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfEnvmapAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFloatVectorAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfKeyCodeAttribute.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfPreviewImageAttribute.h>
#include <OpenEXR/ImfRationalAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfStringVectorAttribute.h>
#include <OpenEXR/ImfTimeCodeAttribute.h>
#include <OpenEXR/ImfVecAttribute.h>
#include <gtest/gtest.h>

#include <cstring>
#include <set>

#include "heightpack/io/read.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

constexpr int kSide = 8;

// One attribute of every type OpenEXR 3.1 registers (but the ID manifest, which it misreads), on a header
// of an 8x8 one-channel float image.
Imf::Header everyAttributeHeader() {
    Imf::Header h(kSide, kSide);
    h.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    h.insert("aBox2f", Imf::Box2fAttribute(Imath::Box2f(Imath::V2f(0, 1), Imath::V2f(2, 3))));
    h.insert("aChromaticities", Imf::ChromaticitiesAttribute(Imf::Chromaticities()));
    h.insert("aDeepImageState", Imf::DeepImageStateAttribute(Imf::DIS_TIDY));
    h.insert("aDouble", Imf::DoubleAttribute(0.25));
    h.insert("aEnvmap", Imf::EnvmapAttribute(Imf::ENVMAP_CUBE));
    h.insert("aFloat", Imf::FloatAttribute(1.5f));
    h.insert("aFloatVector", Imf::FloatVectorAttribute({1.0f, 2.0f, 3.0f}));
    h.insert("aInt", Imf::IntAttribute(7));
    h.insert("aKeyCode", Imf::KeyCodeAttribute(Imf::KeyCode(1, 2, 3, 4, 5, 4, 64)));
    h.insert("aM33d", Imf::M33dAttribute(Imath::M33d()));
    h.insert("aM33f", Imf::M33fAttribute(Imath::M33f()));
    h.insert("aM44d", Imf::M44dAttribute(Imath::M44d()));
    h.insert("aM44f", Imf::M44fAttribute(Imath::M44f()));
    h.insert("aPreview", Imf::PreviewImageAttribute(Imf::PreviewImage(3, 2)));
    h.insert("aRational", Imf::RationalAttribute(Imf::Rational(24000, 1001)));
    h.insert("aString", Imf::StringAttribute("a string of some length"));
    h.insert("aStringVector", Imf::StringVectorAttribute({"one", "", "three"}));
    h.insert("aTimeCode", Imf::TimeCodeAttribute(Imf::TimeCode(1, 2, 3, 4)));
    h.insert("aV2d", Imf::V2dAttribute(Imath::V2d(1, 2)));
    h.insert("aV2f", Imf::V2fAttribute(Imath::V2f(1, 2)));
    h.insert("aV2i", Imf::V2iAttribute(Imath::V2i(1, 2)));
    h.insert("aV3d", Imf::V3dAttribute(Imath::V3d(1, 2, 3)));
    h.insert("aV3f", Imf::V3fAttribute(Imath::V3f(1, 2, 3)));
    h.insert("aV3i", Imf::V3iAttribute(Imath::V3i(1, 2, 3)));
    return h;
}

Imf::FrameBuffer frameOf(std::vector<float>& pixels) {
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data()), sizeof(float), sizeof(float) * kSide));
    return fb;
}

// Written by OpenEXR: every size field is OpenEXR's own.
void writeEveryAttribute(const std::string& path, std::vector<float> pixels, bool multiPart) {
    Imf::Header header = everyAttributeHeader();
    if (!multiPart) {
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(frameOf(pixels));
        out.writePixels(kSide);
        return;
    }
    header.setName("heights");
    header.setType(Imf::SCANLINEIMAGE);
    Imf::Header second = header;
    second.setName("again");
    Imf::MultiPartOutputFile out(path.c_str(), std::vector<Imf::Header>{header, second}.data(), 2);
    for (int part = 0; part < 2; ++part) {
        Imf::OutputPart p(out, part);
        p.setFrameBuffer(frameOf(pixels));
        p.writePixels(kSide);
    }
}

struct AttributeField {
    std::string name, type;
    size_t sizeAt;  // where its 4-byte size field is
    int32_t size;
};

// The first header's attributes, walked from the bytes by the format's definition.
std::vector<AttributeField> attributesOf(const std::vector<unsigned char>& b) {
    std::vector<AttributeField> fields;
    size_t at = 8;
    auto text = [&] {
        const std::string s(reinterpret_cast<const char*>(b.data() + at));
        at += s.size() + 1;
        return s;
    };
    while (b[at] != 0) {
        AttributeField f;
        f.name = text(), f.type = text(), f.sizeAt = at;
        std::memcpy(&f.size, b.data() + at, 4);
        at += 4 + size_t(f.size);
        fields.push_back(f);
    }
    return fields;
}

class ExrHeader : public ::testing::Test {
protected:
    ScratchDir dir;
    const std::vector<float> pixels = randomImage(kSide, kSide, 3).pixels;
};

TEST_F(ExrHeader, EveryAttributeTypeOpenExrWritesLoadsInSingleAndMultiPartFiles) {
    for (bool multiPart : {false, true}) {
        const std::string path = dir.file(multiPart ? "multi.exr" : "single.exr");
        writeEveryAttribute(path, pixels, multiPart);
        auto loaded = loadHeightMap(path);
        ASSERT_TRUE(loaded) << loaded.error().what;
        EXPECT_EQ(loaded->heights.pixels, pixels);
    }
    // The walk below sees all 30 types OpenEXR 3.1 registers but two: tiledesc (this file is not tiled) and
    // idmanifest.
    std::set<std::string> types;
    for (const AttributeField& f : attributesOf(readBytes(dir.file("single.exr")))) types.insert(f.type);
    EXPECT_EQ(types.size(), 28u);
}

// Each attribute's size field one or four bytes off, both ways, in a file whose bytes still hold it:
// wherever OpenEXR would read another number of bytes than the field says, the file is refused as damaged
// naming the attribute; nothing crashes, and whatever loads loads the pixels written.
TEST_F(ExrHeader, AnAttributeWhoseSizeIsNotWhatOpenExrReadsIsRefusedNamingIt) {
    const std::string good = dir.file("good.exr");
    writeEveryAttribute(good, pixels, false);
    const std::vector<unsigned char> bytes = readBytes(good);
    const std::set<std::string> readBySize = {"string", "stringvector"};
    int cases = 0, refusedAsOutOfStep = 0, outOfStep = 0;
    for (const AttributeField& f : attributesOf(bytes)) {
        for (int delta : {-4, -1, 1, 4}) {
            const int32_t size = f.size + delta;
            if (size < 0) continue;
            std::vector<unsigned char> changed = bytes;
            std::memcpy(changed.data() + f.sizeAt, &size, 4);
            const std::string path = dir.file("changed.exr");
            writeBytes(path, changed);
            auto loaded = loadHeightMap(path);
            ++cases;
            if (loaded) {
                EXPECT_EQ(loaded->heights.pixels, pixels) << f.name << " " << delta;
            } else {
                EXPECT_EQ(loaded.error().kind, ErrorKind::BadInput) << f.name;
            }
            // A float vector of whole floats read in whole floats stays in step; so do the strings.
            const bool stillInStep = readBySize.count(f.type) || (f.type == "floatvector" && size % 4 == 0);
            if (stillInStep) continue;
            ++outOfStep;
            if (!loaded && loaded.error().what.find("attribute '" + f.name + "'") != std::string::npos &&
                loaded.error().what.find("does not hold") != std::string::npos)
                ++refusedAsOutOfStep;
            else
                ADD_FAILURE() << f.name << " (" << f.type << ") size " << size << ": "
                              << (loaded ? "loaded" : loaded.error().what);
        }
    }
    EXPECT_GT(cases, 100);
    EXPECT_GT(outOfStep, 90);
    EXPECT_EQ(refusedAsOutOfStep, outOfStep);
}

// The fuzz finding's shape made from a good file: a channel list whose names run past its size field, so
// that OpenEXR would read the next attribute's name from inside it.
TEST_F(ExrHeader, AChannelListRunningPastItsSizeIsRefused) {
    const std::string good = dir.file("good.exr");
    writeEveryAttribute(good, pixels, false);
    std::vector<unsigned char> bytes = readBytes(good);
    for (const AttributeField& f : attributesOf(bytes)) {
        if (f.type != "chlist") continue;
        const int32_t shorter = f.size - 1;  // the list's closing empty name left outside it
        std::memcpy(bytes.data() + f.sizeAt, &shorter, 4);
    }
    writeBytes(dir.file("short_chlist.exr"), bytes);
    auto loaded = loadHeightMap(dir.file("short_chlist.exr"));
    ASSERT_FALSE(loaded);
    EXPECT_NE(loaded.error().what.find("attribute 'channels' of type 'chlist' does not hold"), std::string::npos)
        << loaded.error().what;
}

}  // namespace
