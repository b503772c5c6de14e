#include "support/dav_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

namespace heightpack::test {

namespace fs = std::filesystem;

namespace {

bool connectTo(int port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    const bool connected = ::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
    ::close(fd);
    return connected;
}

std::string nginxProgram() {
    for (const char* candidate : {"/usr/sbin/nginx", "/usr/bin/nginx", "/usr/local/sbin/nginx"})
        if (::access(candidate, X_OK) == 0) return candidate;
    return {};
}

std::string configuration(const std::string& dir, int port) {
    std::ostringstream c;
    c << "daemon off;\nmaster_process off;\n";
    // As root, nginx would serve as 'nobody', who cannot write into this scratch folder.
    if (::geteuid() == 0) c << "user root root;\n";
    c << "pid " << dir << "/nginx.pid;\nerror_log " << dir << "/error.log warn;\n"
      << "events { worker_connections 256; }\n"
      << "http {\n"
      << "  log_format cache '$request_method $uri $status \"$http_authorization\"';\n"
      << "  access_log " << dir << "/access.log cache;\n";
    for (const char* temp : {"client_body", "proxy", "fastcgi", "uwsgi", "scgi"})
      c << "  " << temp << "_temp_path " << dir << "/temp/" << temp << ";\n";
    c << "  server {\n    listen 127.0.0.1:" << port << ";\n    root " << dir << "/www;\n"
      << "    client_max_body_size 0;\n"
      << "    location / { dav_methods PUT DELETE MKCOL; create_full_put_path on; dav_access user:rw; }\n"
      << "    location /broken/ { return 503; }\n"
      << "    location /readonly/ { alias " << dir << "/www/; }\n  }\n}\n";
    return c.str();
}

}  // namespace

int unusedPort() {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = 0;
    socklen_t length = sizeof address;
    ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
    ::close(fd);
    return ntohs(address.sin_port);
}

DavServer::DavServer() {
    const std::string program = nginxProgram();
    if (program.empty()) {
        why_ = "nginx is not installed (scripts/install-deps.sh installs it)";
        return;
    }
    const std::string dir = dir_.path().string();
    fs::create_directories(dir_.path() / "www");
    fs::create_directories(dir_.path() / "temp");
    // A free port can be taken between finding it and nginx binding it: try a few.
    for (int attempt = 0; attempt < 5 && pid_ <= 0; ++attempt) {
        port_ = unusedPort();
        std::ofstream(dir_.file("nginx.conf")) << configuration(dir, port_);
        std::vector<std::string> args = {program, "-e", dir_.file("error.log"), "-c", dir_.file("nginx.conf"), "-p", dir + "/"};
        std::vector<char*> argv;
        for (std::string& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 1, dir_.file("stdout.log").c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        posix_spawn_file_actions_addopen(&actions, 2, dir_.file("stderr.log").c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        pid_t pid = 0;
        const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        if (spawned != 0) {
            why_ = "nginx could not be started";
            return;
        }
        for (int wait = 0; wait < 500; ++wait) {  // up to 5 s
            int status = 0;
            if (::waitpid(pid, &status, WNOHANG) == pid) break;  // exited: the port was taken, or a bad config
            if (connectTo(port_)) {
                pid_ = pid;
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        if (pid_ <= 0) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, nullptr, 0);
        }
    }
    if (pid_ <= 0) {
        std::ifstream log(dir_.file("error.log"));
        std::stringstream text;
        text << log.rdbuf();
        why_ = "nginx did not start: " + text.str();
    }
}

DavServer::~DavServer() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
}

void DavServer::kill() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
}

std::string DavServer::url(const std::string& path) const {
    return "http://127.0.0.1:" + std::to_string(port_) + "/" + path;
}

std::string DavServer::accessLog() const {
    std::ifstream in(dir_.file("access.log"));
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace heightpack::test
