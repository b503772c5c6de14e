// parseCacheLocation: which texts name a folder and which a server, and that a URL's credentials are
// taken out of what may be printed (expected values written out by hand).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "heightpack/bake/build/cache_options.hpp"

using namespace heightpack;

TEST(CacheLocation, FoldersAreAnyTextWithoutAScheme) {
    for (const std::string text : {"out/cache", "/mnt/share/hp-cache", "./a://b", "C:stuff", "http:", "http:/x", "~/.cache/hp"}) {
        auto where = parseCacheLocation(text);
        ASSERT_TRUE(where) << text;
        EXPECT_EQ(where->backend, CacheBackend::Folder) << text;
        EXPECT_EQ(where->where, text);
        EXPECT_TRUE(where->user.empty() && where->password.empty());
    }
}

TEST(CacheLocation, UrlsLoseTheirCredentialsAndTrailingSlashes) {
    struct Case {
        std::string text, where, user, password;
    };
    const std::vector<Case> cases = {
        {"http://cache.studio:8080/hp", "http://cache.studio:8080/hp", "", ""},
        {"HTTPS://cache.studio/hp/", "https://cache.studio/hp", "", ""},
        {"http://artist:s3cret@127.0.0.1:9000/hp//", "http://127.0.0.1:9000/hp", "artist", "s3cret"},
        {"http://a%40b:p%3Aw%25@host/x", "http://host/x", "a@b", "p:w%"},
        {"http://only-user@host", "http://host", "only-user", ""},
        {"http://u:p@ss@host/x", "http://host/x", "u", "p@ss"},
        {"http://[::1]:8080/hp", "http://[::1]:8080/hp", "", ""},
    };
    for (const Case& c : cases) {
        auto where = parseCacheLocation(c.text);
        ASSERT_TRUE(where) << c.text;
        EXPECT_EQ(where->backend, CacheBackend::Http) << c.text;
        EXPECT_EQ(where->where, c.where) << c.text;
        EXPECT_EQ(where->user, c.user) << c.text;
        EXPECT_EQ(where->password, c.password) << c.text;
    }
}

TEST(CacheLocation, OtherSchemesAndBrokenUrlsAreRefusedWithoutRepeatingThem) {
    for (const std::string text : {"", "ftp://u:pw1@host/x", "s3://bucket", "http://", "http://u:pw1@/x", "http://host:80a/x",
                                   "http://host/x?pw1", "http://ho st/x", "http://[::1/x"}) {
        auto where = parseCacheLocation(text);
        ASSERT_FALSE(where) << text;
        EXPECT_EQ(where.error().kind, ErrorKind::InconsistentOptions);
        EXPECT_EQ(where.error().what.find("pw1"), std::string::npos) << where.error().what;
        EXPECT_TRUE(where.error().path.empty());
    }
}
