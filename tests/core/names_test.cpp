// The name tables of core's enums: every name, as users type and see it, parses back to its value.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "heightpack/core/fresnel.hpp"
#include "heightpack/core/layout.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/names.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/core/sea/spectrum.hpp"

using namespace heightpack;

namespace {

// Every entry's name parses back to its value, names are unique, and each has a description.
template <class E>
void expectRoundTrip() {
    for (const EnumName<E>& e : NameTable<E>::entries) {
        EXPECT_STREQ(nameOf(e.value), e.name);
        EXPECT_EQ(parseName<E>(e.name), e.value) << e.name;
        EXPECT_NE(std::string(describe(e.value)), "") << e.name;
    }
    EXPECT_EQ(parseName<E>("no such name"), std::nullopt);
    EXPECT_EQ(parseName<E>(""), std::nullopt);
}

}  // namespace

TEST(Names, EveryTableRoundTrips) {
    expectRoundTrip<Wrap>();
    expectRoundTrip<Filter>();
    expectRoundTrip<SlopeKernel>();
    expectRoundTrip<NormalConvention>();
    expectRoundTrip<NormalAlpha>();
    expectRoundTrip<FresnelModel>();
    expectRoundTrip<FresnelIndex>();
    expectRoundTrip<SpectrumModel>();
    expectRoundTrip<Spreading>();
    expectRoundTrip<Layout>();
}

// The names users type and see, in the order help texts and errors list them: these are a contract.
TEST(Names, NamesAndOrderAreTheDocumentedOnes) {
    using V = std::vector<std::string>;
    EXPECT_EQ(allNames<Wrap>(), (V{"periodic", "clamp"}));
    EXPECT_EQ(allNames<Filter>(), (V{"box", "triangle", "lanczos3", "kaiser"}));
    EXPECT_EQ(allNames<SlopeKernel>(), (V{"central", "sobel3", "scharr"}));
    EXPECT_EQ(allNames<NormalConvention>(), (V{"opengl", "directx"}));
    EXPECT_EQ(allNames<NormalAlpha>(), (V{"none", "height", "variance"}));
    EXPECT_EQ(allNames<FresnelModel>(), (V{"exact", "schlick"}));
    EXPECT_EQ(allNames<FresnelIndex>(), (V{"nv", "2nv"}));
    EXPECT_EQ(allNames<SpectrumModel>(), (V{"phillips", "jonswap", "pierson-moskowitz"}));
    EXPECT_EQ(allNames<Spreading>(), (V{"cos2", "cos2s", "donelan-banner"}));
    EXPECT_EQ(allNames<Layout>(), (V{"neighbour4", "plain", "rgb", "xy"}));
    EXPECT_EQ(joinedNames<Wrap>(), "periodic, clamp");
    EXPECT_EQ(parseName<Wrap>("Clamp"), std::nullopt);  // names are case-sensitive
}

// editDistance against breadth-first searches written from the definitions, over every word of up to four
// letters of a three-letter alphabet: it lies between the fewest edits with swaps of neighbours allowed
// (Damerau) and without them (Levenshtein), and a word one edit away, a swap included, is at 1: the typos
// a "did you mean" must recognise.
TEST(Names, EditDistanceCountsOneLetterEdits) {
    const std::string alphabet = "abc";
    auto neighbours = [&](const std::string& w, bool swaps) {
        std::vector<std::string> out;
        for (size_t i = 0; i <= w.size(); ++i)
            for (char c : alphabet) out.push_back(w.substr(0, i) + c + w.substr(i));  // insert
        for (size_t i = 0; i < w.size(); ++i) {
            out.push_back(w.substr(0, i) + w.substr(i + 1));                               // delete
            for (char c : alphabet) out.push_back(w.substr(0, i) + c + w.substr(i + 1));  // replace
            if (swaps && i + 1 < w.size()) out.push_back(w.substr(0, i) + w[i + 1] + w[i] + w.substr(i + 2));
        }
        return out;
    };
    // The fewest edits from a to every word of up to 5 letters, breadth first.
    auto distancesFrom = [&](const std::string& a, bool swaps) {
        std::map<std::string, size_t> reach = {{a, 0}};
        std::vector<std::string> ring = {a};
        for (size_t d = 1; !ring.empty(); ++d) {
            std::vector<std::string> next;
            for (const std::string& w : ring)
                for (const std::string& n : neighbours(w, swaps))
                    if (n.size() <= 5 && reach.emplace(n, d).second) next.push_back(n);
            ring = next;
        }
        return reach;
    };
    std::vector<std::string> words = {""};
    for (size_t n = 0; n < words.size(); ++n)
        if (words[n].size() < 4)
            for (char c : alphabet) words.push_back(words[n] + c);
    size_t ones = 0;
    for (const std::string& a : words) {
        const auto damerau = distancesFrom(a, true), levenshtein = distancesFrom(a, false);
        for (const std::string& b : words) {
            const size_t d = editDistance(a, b);
            EXPECT_EQ(d, editDistance(b, a)) << a << " " << b;
            EXPECT_LE(damerau.at(b), d) << a << " -> " << b;
            EXPECT_LE(d, levenshtein.at(b)) << a << " -> " << b;
            if (damerau.at(b) <= 1) {
                EXPECT_EQ(d, damerau.at(b)) << a << " -> " << b;
                ones += damerau.at(b);
            }
        }
    }
    EXPECT_GT(ones, words.size());
    EXPECT_EQ(editDistance("tilesize", "tile-size"), 1u);
    EXPECT_EQ(editDistance("fitler", "filter"), 1u);
    EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
    EXPECT_EQ(nearestNames("spreadings", {"wind", "spreading", "spreading-s"}),
              (std::vector<std::string>{"spreading", "spreading-s"}));
    EXPECT_EQ(nearestNames("filtr", {"filter", "fetch", "frames"}), std::vector<std::string>{"filter"});
    EXPECT_TRUE(nearestNames("squash", {"pack", "check"}).empty());
}
