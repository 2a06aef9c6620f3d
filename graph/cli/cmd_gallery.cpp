// `rgraph gallery`: every glTF in a folder rendered into one page — name, image, status and the
// loader's warnings or error — to see at a glance what a collection of assets does in rgraph.
// Each model renders in a child `rgraph render`, so that one that crashes or hangs is reported on
// the page instead of taking the others down.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"
#include "golden/report.h"

extern char** environ;

namespace rg::cli {

namespace {

const char* const kHelp =
    "usage: rgraph gallery DIR [--out PAGE.html] [--size WxH] [--frames N] [--pipeline FILE.lua]\n"
    "                      [--set NAME=VALUE]... [--timeout SECONDS]\n\n"
    "Renders every .gltf and .glb under DIR (sorted by path) with `rgraph render`, each in a "
    "process of its\nown, and writes one page: each model's name, image, status and what the "
    "loader said. Status:\n"
    "ok, warnings (rendered; the loader named what it skipped or changed), refused (bad input: "
    "the\nloader's reason), failed (a device failure or validation messages), crashed (a signal) "
    "or timed out.\n"
    "--out: the page (default DIR/gallery.html); the images and logs go to the folder beside it "
    "named\nPAGE_files. --size: each image (default 320x240). --frames: frames per model "
    "(default 8, so that\nthe exposure and TAA settle). --timeout: seconds per model (default "
    "300). --pipeline and --set as\nfor render.\n"
    "Exit: 0 when every model rendered or was refused with a reason, 1 when one failed, "
    "crashed or timed out,\n2 for bad usage or a folder without glTF files.\n";

struct Entry {
    std::string name;  // path under DIR
    std::string file;  // as given to render
    std::string image, log;
    std::string status;
    std::vector<std::string> warnings;
    std::string error;
    double seconds = 0.0;
};

using golden::htmlEscape;

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
    if (from.empty()) return s;
    for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
        s.replace(at, from.size(), to);
    return s;
}

// Runs argv with stdout and stderr into `log`; the exit status as waitpid gives it, or -1 when
// it ran past `timeout` seconds (then killed).
int runChild(const std::vector<std::string>& argv, const std::string& log, double timeout) {
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, "/proc/self/exe", &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return -2;
    const auto start = std::chrono::steady_clock::now();
    for (;;) {
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid) return status;
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
            timeout) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            return -1;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

void readLog(Entry& e, const std::string& shownPath) {
    std::ifstream in(e.log);
    std::string line;
    while (std::getline(in, line)) {
        line = replaceAll(line, shownPath, e.name);
        if (line.rfind("rgraph: warning: ", 0) == 0)
            e.warnings.push_back(line.substr(17));
        else if (line.rfind("rgraph: error: ", 0) == 0)
            e.error = line.substr(15);
        else if (!e.error.empty() && !line.empty() && line[0] == ' ')
            e.error += "\n" + line;  // an error's indented reasons
    }
}

std::string seconds(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f s", s);
    return buf;
}

bool writePage(const std::string& path, const std::string& dir, const std::string& files,
               const std::vector<Entry>& entries, const std::string& settings) {
    std::map<std::string, int> counts;
    for (const auto& e : entries) ++counts[e.status];
    std::ostringstream o;
    o << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>rgraph gallery: "
      << htmlEscape(dir) << "</title>\n<style>\n"
      << "body{font-family:sans-serif;background:#1d1f23;color:#ddd;margin:16px}\n"
      << "h1{font-size:20px} .grid{display:flex;flex-wrap:wrap;gap:12px}\n"
      << ".card{background:#2a2d33;border-radius:6px;padding:8px;width:340px}\n"
      << ".card img{display:block;max-width:100%;border-radius:3px;background:#000}\n"
      << ".none{height:120px;display:flex;align-items:center;justify-content:center;color:#888}\n"
      << ".name{font-weight:bold;margin:4px 0;word-break:break-all}\n"
      << ".status{display:inline-block;padding:1px 6px;border-radius:3px;font-size:12px}\n"
      << ".ok{background:#2e7d32}.warnings{background:#9a7d0a}.refused{background:#555}\n"
      << ".failed,.crashed,.timed-out{background:#b71c1c}\n"
      << "ul{margin:4px 0;padding-left:18px;font-size:12px;color:#e0c060}\n"
      << "pre{white-space:pre-wrap;font-size:12px;color:#f08080;margin:4px 0}\n"
      << "</style></head><body>\n<h1>rgraph gallery: " << htmlEscape(dir) << "</h1>\n<p>"
      << entries.size() << " models:";
    for (const char* s : {"ok", "warnings", "refused", "failed", "crashed", "timed out"})
        if (counts.count(s)) o << " " << counts[s] << " " << s << ",";
    o.seekp(-1, std::ios_base::cur);
    o << ". " << htmlEscape(settings) << "</p>\n<div class=\"grid\">\n";
    for (const auto& e : entries) {
        std::string cls = replaceAll(e.status, " ", "-");
        o << "<div class=\"card\">";
        if (!e.image.empty())
            o << "<img src=\"" << htmlEscape(files + "/" + e.image) << "\" alt=\""
              << htmlEscape(e.name) << "\">";
        else
            o << "<div class=\"none\">no image</div>";
        o << "<div class=\"name\">" << htmlEscape(e.name) << "</div><span class=\"status " << cls
          << "\">" << e.status << "</span> <small>" << seconds(e.seconds) << "</small>";
        if (!e.error.empty()) o << "<pre>" << htmlEscape(e.error) << "</pre>";
        if (!e.warnings.empty()) {
            o << "<ul>";
            for (const auto& w : e.warnings) o << "<li>" << htmlEscape(w) << "</li>";
            o << "</ul>";
        }
        o << "</div>\n";
    }
    o << "</div>\n</body></html>\n";
    std::ofstream out(path);
    out << o.str();
    return out.good();
}

}  // namespace

int cmdGallery(int argc, char** argv) {
    Args args;
    // DIR first, then the options: they are read from after it (--help works without one).
    const int dirFirst = argc >= 3 && argv[2][0] != '-' ? 1 : 0;
    if (auto done =
            parseCommand(argc - dirFirst, argv + dirFirst, "gallery",
                         {"out", "size", "frames", "pipeline", "set", "timeout"}, kHelp, args))
        return *done;
    if (!dirFirst) return usageError("gallery needs a folder (rgraph gallery DIR)", "gallery");
    const std::string dir = argv[2];
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return usageError("'" + dir + "' is not a folder", "gallery");
    uint32_t w = 320, h = 240, frames = 8, timeout = 300;
    if (args.has("size") && !parseSize(args.get("size"), w, h))
        return usageError("--size '" + args.get("size") + "': expected WxH", "gallery");
    if (args.has("frames") && !parseCount(args.get("frames"), frames))
        return usageError("--frames '" + args.get("frames") + "': expected a number >= 1",
                          "gallery");
    if (args.has("timeout") && !parseCount(args.get("timeout"), timeout))
        return usageError("--timeout '" + args.get("timeout") + "': expected seconds >= 1",
                          "gallery");
    std::vector<Entry> entries;
    for (auto it = fs::recursive_directory_iterator(dir, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        const std::string ext = it->path().extension().string();
        if (!it->is_regular_file(ec) || (ext != ".gltf" && ext != ".glb")) continue;
        Entry e;
        e.file = it->path().string();
        e.name = fs::relative(it->path(), dir, ec).generic_string();
        entries.push_back(e);
    }
    if (entries.empty()) return usageError("no .gltf or .glb files under '" + dir + "'", "gallery");
    std::sort(entries.begin(), entries.end(),
              [](const Entry& a, const Entry& b) { return a.name < b.name; });
    const fs::path page = args.get("out", (fs::path(dir) / "gallery.html").string());
    const std::string filesName = page.stem().string() + "_files";
    const fs::path files = page.parent_path() / filesName;
    fs::create_directories(files, ec);
    if (ec)
        return report(
            Error{ErrorCode::Io, "cannot create '" + files.string() + "': " + ec.message()});
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    int worst = kOk;
    for (size_t i = 0; i < entries.size(); ++i) {
        Entry& e = entries[i];
        const std::string stem = replaceAll(e.name, "/", "__");
        const fs::path exr = files / (stem + ".exr");
        e.log = (files / (stem + ".log")).string();
        std::vector<std::string> cmd = {"rgraph", "render",    "--scene",  e.file,
                                        "--size", size,        "--frames", std::to_string(frames),
                                        "--out",  exr.string()};
        if (args.has("pipeline")) cmd.insert(cmd.end(), {"--pipeline", args.get("pipeline")});
        for (const auto& s : args.all("set")) cmd.insert(cmd.end(), {"--set", s});
        const auto t0 = std::chrono::steady_clock::now();
        const int status = runChild(cmd, e.log, double(timeout));
        e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        readLog(e, e.file);
        if (status == -1) {
            e.status = "timed out";
        } else if (status == -2) {
            e.status = "failed";
            e.error = "could not start rgraph render";
        } else if (WIFSIGNALED(status)) {
            e.status = "crashed";
            e.error = std::string("signal ") + std::to_string(WTERMSIG(status)) +
                      (e.error.empty() ? "" : "\n" + e.error);
        } else if (WEXITSTATUS(status) == kOk) {
            e.status = e.warnings.empty() ? "ok" : "warnings";
            e.image = stem + ".png";
        } else {
            e.status = WEXITSTATUS(status) == kUsage ? "refused" : "failed";
        }
        if (e.status != "ok" && e.status != "warnings" && e.status != "refused") worst = kFailed;
        std::fprintf(stderr, "rgraph: gallery [%zu/%zu] %s: %s (%.1f s)\n", i + 1, entries.size(),
                     e.name.c_str(), e.status.c_str(), e.seconds);
    }
    const fs::path shown = fs::path(dir).lexically_normal();
    if (!writePage(page.string(),
                   (shown.has_filename() ? shown : shown.parent_path()).filename().string(),
                   filesName, entries,
                   size + ", " + std::to_string(frames) + " frames" +
                       (args.has("pipeline") ? ", " + logicalName(args.get("pipeline")) : "")))
        return report(Error{ErrorCode::Io, "cannot write '" + page.string() + "'"});
    std::printf("rgraph: wrote %s (%zu models)\n", page.string().c_str(), entries.size());
    return worst;
}

}  // namespace rg::cli
