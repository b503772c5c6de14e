// An nginx WebDAV server for tests that need an HTTP cache (GET, PUT): started on 127.0.0.1 at a free
// port, with its own configuration, logs, temporary files and served folder in a scratch folder, so it
// runs as any user; stopped by its process id. Debian's nginx has the DAV module built in.
#pragma once

#include <sys/types.h>

#include <string>

#include "support/test_support.hpp"

namespace heightpack::test {

class DavServer {
public:
    // Starts nginx and waits until it accepts connections; started() says whether it did (why() if not).
    DavServer();
    ~DavServer();  // stops it, if still running
    DavServer(const DavServer&) = delete;
    DavServer& operator=(const DavServer&) = delete;

    bool started() const { return pid_ > 0; }
    const std::string& why() const { return why_; }
    int port() const { return port_; }
    // http://127.0.0.1:PORT/path. Under /broken/ every request is answered 503; /readonly/ serves what
    // "/" holds and refuses PUT (405), as a server that lets this user read only.
    std::string url(const std::string& path) const;
    // The folder served at "/": what PUTs wrote, to look at or damage.
    std::string root() const { return dir_.file("www"); }
    // One line per request: "METHOD URI STATUS AUTHORIZATION-HEADER".
    std::string accessLog() const;
    // Kills nginx at once (SIGKILL), as a server that dies does, and waits for it.
    void kill();

private:
    ScratchDir dir_;
    pid_t pid_ = -1;
    int port_ = 0;
    std::string why_;
};

// A port on 127.0.0.1 that nothing listens on (it was free a moment ago).
int unusedPort();

}  // namespace heightpack::test
