#include "heightpack/bake/cache_options.hpp"

#include <curl/curl.h>

#include <algorithm>
#include <cctype>
#include <memory>

namespace heightpack {

namespace {

constexpr const char* kHint = "name a folder, or an http:// or https:// URL";

// A part of a parsed URL ("" where it has none), percent-decoded when asked.
std::string urlPart(CURLU* url, CURLUPart part, unsigned flags = 0) {
    char* text = nullptr;
    if (curl_url_get(url, part, &text, flags) != CURLUE_OK || !text) return {};
    std::string value = text;
    curl_free(text);
    return value;
}

}  // namespace

Result<CacheLocation> parseCacheLocation(const std::string& text) {
    if (text.empty()) return inconsistentOptions("", "the cache is named by an empty text", kHint);
    // "scheme://..." is a URL; anything else ("out/cache", "./a://b", "C:stuff") a folder.
    const auto colon = text.find("://");
    std::string scheme = colon == std::string::npos ? std::string() : text.substr(0, colon);
    const bool url = !scheme.empty() && std::all_of(scheme.begin(), scheme.end(), [](unsigned char c) {
        return std::isalnum(c) || c == '+' || c == '-' || c == '.';
    });
    if (!url) return CacheLocation{CacheBackend::Folder, text, {}, {}};
    std::transform(scheme.begin(), scheme.end(), scheme.begin(), [](unsigned char c) { return std::tolower(c); });
    if (scheme != "http" && scheme != "https")
        return inconsistentOptions("", "the cache's URL scheme '" + scheme + "' is not one heightpack speaks (http, https)", kHint);

    const std::unique_ptr<CURLU, void (*)(CURLU*)> parsed(curl_url(), curl_url_cleanup);
    if (!parsed || curl_url_set(parsed.get(), CURLUPART_URL, text.c_str(), 0) != CURLUE_OK ||
        urlPart(parsed.get(), CURLUPART_HOST).empty())
        return inconsistentOptions("", "the cache's URL cannot be parsed", kHint);  // never the text: it may hold a password
    CacheLocation location;
    location.backend = CacheBackend::Http;
    location.user = urlPart(parsed.get(), CURLUPART_USER, CURLU_URLDECODE);
    location.password = urlPart(parsed.get(), CURLUPART_PASSWORD, CURLU_URLDECODE);
    curl_url_set(parsed.get(), CURLUPART_USER, nullptr, 0);
    curl_url_set(parsed.get(), CURLUPART_PASSWORD, nullptr, 0);
    curl_url_set(parsed.get(), CURLUPART_OPTIONS, nullptr, 0);
    location.where = urlPart(parsed.get(), CURLUPART_URL);
    while (location.where.ends_with('/')) location.where.pop_back();
    if (location.where.empty()) return inconsistentOptions("", "the cache's URL cannot be parsed", kHint);
    return location;
}

}  // namespace heightpack
