// The name tables of core's enums: every name, as users type and see it, parses back to its value.
#include <gtest/gtest.h>

#include "heightpack/core/fresnel.hpp"
#include "heightpack/core/layout.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/names.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/core/spectrum.hpp"

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
