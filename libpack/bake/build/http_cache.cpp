#include "http_cache.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "heightpack/bake/build/build_state.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/version.hpp"

#include "cache_entry.hpp"
#include "curl_library.hpp"

namespace heightpack::detail {

namespace {

// The handles of one request, released whatever happens.
struct Request {
    const CurlLibrary& lib;
    CURL* curl = lib.easyInit();
    curl_slist* headers = nullptr;
    explicit Request(const CurlLibrary& library) : lib(library) {}
    Request(const Request&) = delete;
    Request& operator=(const Request&) = delete;
    ~Request() {
        lib.slistFreeAll(headers);
        if (curl) lib.easyCleanup(curl);
    }
    template <class Value>
    void set(CURLoption option, Value value) {
        lib.easySetopt(curl, option, value);
    }
    template <class Value>
    void get(CURLINFO info, Value* value) {
        lib.easyGetinfo(curl, info, value);
    }
};

struct Fd {
    int fd = -1;
    explicit Fd(int f) : fd(f) {}
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

// A request to url with the server's timeouts and credentials. The credentials go in options of their
// own, never into the URL, so no message libcurl makes can hold them.
void prepare(Request& r, const HttpServer& server, const std::string& url) {
    static const std::string agent = std::string("heightpack/") + kVersion;
    r.set(CURLOPT_URL, url.c_str());
    r.set(CURLOPT_PROTOCOLS_STR, "http,https");
    r.set(CURLOPT_USERAGENT, agent.c_str());
    r.set(CURLOPT_NOSIGNAL, 1L);  // timeouts without SIGALRM: requests run on several threads
    r.set(CURLOPT_CONNECTTIMEOUT_MS, static_cast<long>(server.connectMilliseconds));
    // A server that accepted the connection but sends (or takes) nothing for stallSeconds is down.
    r.set(CURLOPT_LOW_SPEED_LIMIT, 1L);
    r.set(CURLOPT_LOW_SPEED_TIME, static_cast<long>(server.stallSeconds));
    if (!server.token.empty()) {
        r.headers = r.lib.slistAppend(r.headers, ("Authorization: Bearer " + server.token).c_str());
    } else if (!server.user.empty() || !server.password.empty()) {
        r.set(CURLOPT_HTTPAUTH, CURLAUTH_BASIC);
        r.set(CURLOPT_USERNAME, server.user.c_str());
        r.set(CURLOPT_PASSWORD, server.password.c_str());
    }
    // No "Expect: 100-continue" wait before a PUT's body: a cache entry is sent whole either way.
    r.headers = r.lib.slistAppend(r.headers, "Expect:");
    r.set(CURLOPT_HTTPHEADER, r.headers);
}

// What a failed transfer says about the server, in words without its address or credentials.
ServerFailure transferFailure(Request& r, CURLcode code, const HttpServer& server) {
    curl_off_t connected = 0;
    r.get(CURLINFO_CONNECT_TIME_T, &connected);
    std::string why;
    if (code == CURLE_COULDNT_CONNECT)
        why = "refuses connections (not running, or nothing listens on its port)";
    else if (code == CURLE_COULDNT_RESOLVE_HOST)
        why = "its host name does not resolve";
    else if (code == CURLE_OPERATION_TIMEDOUT && connected == 0)
        why = "did not accept a connection within " + std::to_string(server.connectMilliseconds) + " ms";
    else if (code == CURLE_OPERATION_TIMEDOUT)
        why = "stalled: nothing came or went for " + std::to_string(server.stallSeconds) + " s";
    else
        why = std::string("cannot be reached (") + r.lib.easyStrerror(code) + ")";
    return {ServerTrouble::Down, why};
}

// What an answer that is neither success nor "not here" says about the server.
ServerFailure statusFailure(long status) {
    std::string why = "answered HTTP " + std::to_string(status);
    if (status == 401 || status == 403) why += " (credentials missing, wrong or not allowed this)";
    if (status == 405 || status == 501) why += " (it does not take this method: a WebDAV or cache server does)";
    return {status >= 500 ? ServerTrouble::Down : ServerTrouble::Refused, why};
}

// A GET's body: its first kEntryHeaderBytes kept as the header, the rest written to fd. Only a 200's body
// is kept (an error page is nobody's entry).
struct Download {
    Request* request = nullptr;
    int fd = -1;
    std::string header;
    std::uint64_t bytes = 0;
    int writeErrno = 0;
};

size_t onBody(char* data, size_t size, size_t count, void* user) {
    auto& d = *static_cast<Download*>(user);
    const size_t n = size * count;
    long status = 0;
    d.request->get(CURLINFO_RESPONSE_CODE, &status);
    if (status != 200) return n;
    size_t at = 0;
    if (d.header.size() < kEntryHeaderBytes) {
        at = std::min(n, static_cast<size_t>(kEntryHeaderBytes - d.header.size()));
        d.header.append(data, at);
    }
    while (at < n) {
        const ssize_t w = ::write(d.fd, data + at, n - at);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            d.writeErrno = w < 0 ? errno : EIO;
            return 0;  // ends the transfer (CURLE_WRITE_ERROR)
        }
        at += static_cast<size_t>(w);
    }
    d.bytes += n;
    return n;
}

// A PUT's body: the header, then the source's bytes.
struct Upload {
    const std::string* header = nullptr;
    int fd = -1;
    std::uint64_t at = 0;
};

size_t onSend(char* buffer, size_t size, size_t count, void* user) {
    auto& u = *static_cast<Upload*>(user);
    const size_t room = size * count;
    if (u.at < u.header->size()) {
        const size_t n = std::min(room, static_cast<size_t>(u.header->size() - u.at));
        std::memcpy(buffer, u.header->data() + u.at, n);
        u.at += n;
        return n;
    }
    for (;;) {
        const ssize_t n = ::pread(u.fd, buffer, room, static_cast<off_t>(u.at - u.header->size()));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return CURL_READFUNC_ABORT;
        u.at += static_cast<std::uint64_t>(n);
        return static_cast<size_t>(n);
    }
}

std::string entryUrl(const HttpServer& server, const std::string& key, const std::string& output) {
    return server.url + "/" + entryName(key, output);
}

}  // namespace

std::string initialiseHttp() {
    std::string why;
    curlLibrary(why);
    return why;
}

Result<CacheLookup> restoreFromServer(const HttpServer& server, const std::string& key, const std::string& output,
                                      const std::string& destination, ServerFailure& failure) {
    CacheLookup lookup;
    const CurlLibrary* lib = curlLibrary(failure.why);
    if (!lib) {
        failure.trouble = ServerTrouble::Down;
        lookup.unavailable = true;
        return lookup;
    }
    Request r(*lib);
    if (!r.curl) return Error{ErrorKind::Internal, destination, "libcurl could not start a request", "please report this"};
    prepare(r, server, entryUrl(server, key, output));
    TemporaryFile temp(destination);
    const Fd out(::open(temp.path().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666));
    if (out.fd < 0) return cannotWrite(destination, std::string("cannot be written: ") + std::strerror(errno));
    Download d;
    d.request = &r;
    d.fd = out.fd;
    r.set(CURLOPT_WRITEFUNCTION, onBody);
    r.set(CURLOPT_WRITEDATA, &d);
    const CURLcode code = r.lib.easyPerform(r.curl);
    if (d.writeErrno == ENOSPC || d.writeErrno == EDQUOT)
        return cannotWrite(destination, std::string("cannot be written: ") + std::strerror(d.writeErrno), "free some disk space");
    if (d.writeErrno != 0) return cannotWrite(destination, std::string("cannot be written: ") + std::strerror(d.writeErrno));
    if (code != CURLE_OK) {
        failure = transferFailure(r, code, server);
        lookup.unavailable = true;
        return lookup;
    }
    long status = 0;
    r.get(CURLINFO_RESPONSE_CODE, &status);
    if (status == 404 || status == 410) return lookup;  // not there: a miss
    if (status != 200) {
        failure = statusFailure(status);
        lookup.unavailable = true;
        return lookup;
    }
    std::uint64_t size = 0;
    std::string hash;
    lookup.rejected = judgeEntryHeader(d.header, d.bytes, key, output, size, hash);
    if (!lookup.rejected.empty()) return lookup;
    auto landed = hashFile(temp.path());
    if (!landed || *landed != hash) {
        lookup.rejected = "its bytes do not match the hash in its header (altered)";
        return lookup;
    }
    if (Status s = temp.commit(); !s) return s.error();
    lookup.hit = true;
    lookup.hash = hash;
    return lookup;
}

Status storeOnServer(const HttpServer& server, const std::string& key, const std::string& output,
                     const std::string& source, const std::string& hash, ServerFailure& failure) {
    const std::string url = entryUrl(server, key, output);
    const Fd in(::open(source.c_str(), O_RDONLY | O_CLOEXEC));
    struct stat st {};
    if (in.fd < 0 || ::fstat(in.fd, &st) != 0) return badInput(source, "cannot be read to store it in the cache");
    const std::string header = entryHeader(key, output, static_cast<std::uint64_t>(st.st_size), hash);
    if (header.empty()) return cannotWrite(url, "the entry's header would not fit its 4096 bytes (a very long output name)");
    const CurlLibrary* lib = curlLibrary(failure.why);
    if (!lib) {
        failure.trouble = ServerTrouble::Down;
        return cannotWrite(server.url, failure.why);
    }
    Request r(*lib);
    if (!r.curl) return Error{ErrorKind::Internal, url, "libcurl could not start a request", "please report this"};
    prepare(r, server, url);
    Upload u{&header, in.fd, 0};
    r.set(CURLOPT_UPLOAD, 1L);  // PUT
    r.set(CURLOPT_INFILESIZE_LARGE, static_cast<curl_off_t>(header.size() + st.st_size));
    r.set(CURLOPT_READFUNCTION, onSend);
    r.set(CURLOPT_READDATA, &u);
    // The answer's body (an error page, or nothing) is not needed.
    r.set(CURLOPT_WRITEFUNCTION, +[](char*, size_t size, size_t count, void*) { return size * count; });
    const CURLcode code = r.lib.easyPerform(r.curl);
    if (code == CURLE_ABORTED_BY_CALLBACK) return badInput(source, "could not be read to store it in the cache");
    long status = 0;
    if (code == CURLE_OK) r.get(CURLINFO_RESPONSE_CODE, &status);
    if (code == CURLE_OK && status >= 200 && status < 300) return Done{};
    failure = code != CURLE_OK ? transferFailure(r, code, server) : statusFailure(status);
    return cannotWrite(server.url, failure.why);
}

}  // namespace heightpack::detail
