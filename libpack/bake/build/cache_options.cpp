#include "heightpack/bake/build/cache_options.hpp"

#include <algorithm>
#include <cctype>

namespace heightpack {

namespace {

constexpr const char* kHint = "name a folder, or an http:// or https:// URL";

// %XX sequences turned into their bytes (a user or password in a URL may hold ':' or '@' so spelt).
std::string percentDecoded(std::string_view text) {
    std::string out;
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '%' && i + 2 < text.size() && std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
            out += static_cast<char>(std::stoi(std::string(text.substr(i + 1, 2)), nullptr, 16));
            i += 2;
        } else {
            out += text[i];
        }
    }
    return out;
}

bool hostCharacter(unsigned char c) { return std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '%'; }

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

    // scheme://[user[:password]@]host[:port][/path]. The errors never repeat the text: it may hold a password.
    const std::string rest = text.substr(colon + 3);
    const size_t pathAt = std::min(rest.find_first_of("/?#"), rest.size());
    const std::string authority = rest.substr(0, pathAt);
    const std::string path = rest.substr(pathAt);
    const size_t at = authority.rfind('@');
    const std::string userInfo = at == std::string::npos ? std::string() : authority.substr(0, at);
    const std::string hostPort = at == std::string::npos ? authority : authority.substr(at + 1);
    std::string host = hostPort, port;
    if (hostPort.starts_with('[')) {  // [IPv6]:port
        const size_t close = hostPort.find(']');
        host = close == std::string::npos ? std::string() : hostPort.substr(0, close + 1);
        if (close != std::string::npos && close + 1 < hostPort.size()) {
            if (hostPort[close + 1] != ':') host.clear();
            port = hostPort.substr(close + 2);
        }
    } else if (const size_t portAt = hostPort.rfind(':'); portAt != std::string::npos) {
        host = hostPort.substr(0, portAt);
        port = hostPort.substr(portAt + 1);
    }
    const bool hostOk = !host.empty() && (host.starts_with('[') || std::all_of(host.begin(), host.end(), hostCharacter));
    const bool portOk = port.size() <= 5 && std::all_of(port.begin(), port.end(), [](unsigned char c) { return std::isdigit(c); });
    const bool printable = std::all_of(text.begin(), text.end(), [](unsigned char c) { return c > 0x20 && c != 0x7f; });
    if (!hostOk || !portOk || !printable || path.find_first_of("?#") != std::string::npos)
        return inconsistentOptions("", "the cache's URL cannot be parsed (scheme://host[:port]/path, no query)", kHint);

    CacheLocation location;
    location.backend = CacheBackend::Http;
    const size_t split = userInfo.find(':');
    location.user = percentDecoded(userInfo.substr(0, split));
    if (split != std::string::npos) location.password = percentDecoded(userInfo.substr(split + 1));
    location.where = scheme + "://" + hostPort + path;
    while (location.where.ends_with('/')) location.where.pop_back();
    return location;
}

}  // namespace heightpack
