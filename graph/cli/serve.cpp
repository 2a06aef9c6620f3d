#include "serve.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <mutex>
#include <random>
#include <thread>

#include <malloc.h>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "image/image.h"
#include "file_watch.h"
#include "serve_page.h"

namespace rg {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

json valueJson(const Value& v) {
    if (v.isBool()) return v.asBool();
    if (v.isNumber()) return v.asNumber();
    if (v.isString()) return v.asString();
    json list = json::array();
    for (const Value& e : v.asList()) list.push_back(valueJson(e));
    return list;
}

// A request body's value as the parameter's type wants it (numbers, booleans, strings, [x,y,z]).
Result<Value> jsonValue(const json& j) {
    if (j.is_boolean()) return Value(j.get<bool>());
    if (j.is_number()) return Value(j.get<double>());
    if (j.is_string()) return Value(j.get<std::string>());
    if (j.is_array()) {
        Value::List list;
        for (const auto& e : j) {
            if (!e.is_number())
                return fail(ErrorCode::InvalidInput, "value: a list holds numbers only");
            list.push_back(Value(e.get<double>()));
        }
        return Value(list);
    }
    return fail(ErrorCode::InvalidInput,
                "value: expected a number, a boolean, a string or a list of numbers");
}

// What the page shows of the running pipeline, gathered on the render thread after each frame.
json stateJson(Runtime& runtime, const Session& session, uint64_t frames, const std::string& error,
               double frameMs) {
    const gpu::Executor& ex = runtime.executor();
    const PipelineDesc& p = session.pipeline();
    json state;
    state["pipeline"] = p.file;
    state["frame"] = frames;
    state["frameMs"] = frameMs;
    state["error"] = error.empty() ? json(nullptr) : json(error);
    const auto& report = ex.lastBuildReport();
    state["rebuilt"] = report.passesPrepared.size();
    state["reused"] = report.passesReused.size();
    state["buildSummary"] = report.summary();
    std::map<std::string, double> gpu, cpu;
    for (const auto& t : ex.lastTimings()) {
        gpu[t.name] = t.gpuMs;
        cpu[t.name] = t.cpuMs;
    }
    json passes = json::array();
    for (const PassDesc& d : p.graph.passes) {
        const bool kept = std::any_of(ex.plan().passes.begin(), ex.plan().passes.end(),
                                      [&](const PlanPass& q) { return q.name == d.name; });
        passes.push_back({{"name", d.name},
                          {"kind", d.kind},
                          {"enabled", d.enabled},
                          {"kept", kept},
                          {"gpuMs", gpu.count(d.name) ? json(gpu[d.name]) : json(nullptr)},
                          {"cpuMs", cpu.count(d.name) ? json(cpu[d.name]) : json(nullptr)},
                          {"origin", d.origin}});
    }
    state["passes"] = passes;
    json params = json::array();
    for (const ParamDesc& d : p.params) {
        json j{{"name", d.name},
               {"type", paramTypeName(d.type)},
               {"value", valueJson(d.value)},
               {"doc", d.doc}};
        if (d.min > -1e299) j["min"] = d.min;
        if (d.max < 1e299) j["max"] = d.max;
        if (!d.choices.empty()) j["choices"] = d.choices;
        params.push_back(j);
    }
    state["params"] = params;
    json textures = json::array();
    for (const PlanResource& r : ex.plan().resources)
        if (r.kind == ResourceKind::Texture) textures.push_back(r.name);
    for (const LayoutDesc& l : p.layouts)
        for (const TargetDesc& t : l.targets)
            for (const ChannelDesc& c : t.channels) textures.push_back(l.name + "." + c.name);
    state["textures"] = textures;
    state["hdr"] = p.hdr;
    state["display"] = p.output;
    return state;
}

// A texture as a display image: RGB (one or two channels repeated), linear float formats times
// 2^ev and sRGB-encoded, 8-bit unorm shown as stored; NaN as magenta.
Image displayImage(const Image& in, Format format, float ev, bool decoded) {
    const FormatInfo& f = formatInfo(format);
    const bool linear =
        decoded || f.floating || f.depth || f.srgb;  // sRGB textures read back linear
    const float scale = std::exp2(ev);
    Image out(in.width, in.height, 3);
    for (size_t i = 0; i < size_t(in.width) * in.height; ++i)
        for (uint32_t c = 0; c < 3; ++c) {
            float v = in.pixels[i * in.channels + std::min(c, in.channels - 1)];
            if (in.channels == 2 && c == 2) v = 0.0f;
            if (std::isnan(v)) v = c == 1 ? 0.0f : 1.0f;
            out.pixels[i * 3 + c] =
                linear ? srgbEncode(std::clamp(v * scale, 0.0f, 1.0f)) : std::clamp(v, 0.0f, 1.0f);
        }
    return out;
}

// A name from a request, quoted in an answer: never longer than a line.
std::string quoted(const std::string& name) {
    return "'" + (name.size() > 80 ? name.substr(0, 80) + "…" : name) + "'";
}

// The body of a POST as JSON, or why it is not: a number out of a double's range is named as
// such rather than reported as bad syntax.
Result<json> parseBody(const std::string& body) {
    try {
        return json::parse(body);
    } catch (const json::out_of_range& e) {
        return fail(ErrorCode::InvalidInput,
                    "value: a number out of range (beyond ±1.8e308): " + std::string(e.what()));
    } catch (const json::exception&) {
        return fail(ErrorCode::InvalidInput, "the body is not JSON (expected a JSON object)");
    }
}

// Constant-time comparison, so that answer times say nothing about a token's prefix.
bool sameToken(const std::string& a, const std::string& b) {
    if (a.size() != b.size() || a.empty()) return false;
    unsigned char d = 0;
    for (size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned char>(a[i] ^ b[i]);
    return d == 0;
}

// The value of cookie `name` in a Cookie header ("a=1; rgraph_token=…").
std::string cookie(const std::string& header, const std::string& name) {
    size_t at = 0;
    while (at < header.size()) {
        size_t end = header.find(';', at);
        if (end == std::string::npos) end = header.size();
        std::string part = header.substr(at, end - at);
        const size_t first = part.find_first_not_of(' ');
        if (first != std::string::npos) part = part.substr(first);
        if (part.compare(0, name.size() + 1, name + "=") == 0) return part.substr(name.size() + 1);
        at = end + 1;
    }
    return {};
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

static std::string randomToken() {
    std::random_device device;
    std::string token;
    static const char* hex = "0123456789abcdef";
    for (int i = 0; i < 12; ++i) {
        const uint32_t v = device();
        for (int k = 0; k < 4; ++k) token += hex[(v >> (k * 4)) & 15];
    }
    return token;
}

static bool isLoopback(const std::string& host) {
    return host == "127.0.0.1" || host == "localhost" || host == "::1" ||
           host.rfind("127.", 0) == 0;
}

int serve(Runtime& runtime, Session& session, const ServeOptions& options) {
    if (!options.tokenGiven && !isLoopback(options.host)) {
        std::fprintf(stderr,
                     "rgraph: serve: --host %s is not a loopback address: give --token TOKEN, "
                     "which every client then needs\n",
                     options.host.c_str());
        return 2;
    }
    const std::string token = options.tokenGiven ? options.token : randomToken();
    if (token.empty()) {
        std::fprintf(stderr, "rgraph: serve: --token must not be empty\n");
        return 2;
    }

    // The render thread owns the session; HTTP handlers hand it jobs and wait for their answers.
    // From shutdown on, a job is answered 503 "shutting down" instead of run.
    struct Job {
        std::function<httplib::Response()> work;
        std::promise<httplib::Response> answer;
    };
    std::mutex mutex;
    std::deque<std::shared_ptr<Job>> jobs;
    bool stopping = false;
    json state;
    std::string lastError;
    uint64_t frames = 0;

    auto jsonResponse = [](int status, const json& body) {
        httplib::Response r;
        r.status = status;
        r.set_content(body.dump(), "application/json");
        return r;
    };
    auto run = [&](std::function<httplib::Response()> work) {
        auto job = std::make_shared<Job>();
        job->work = std::move(work);
        auto answer = job->answer.get_future();
        {
            std::lock_guard lock(mutex);
            if (stopping) return jsonResponse(503, {{"error", "shutting down"}});
            jobs.push_back(job);
        }
        if (answer.wait_for(std::chrono::seconds(30)) != std::future_status::ready) {
            // Not started in 30 s: taken out of the queue, so that a request answered 503 never
            // takes effect later. One the render thread has started is waited for.
            std::lock_guard lock(mutex);
            if (auto it = std::find(jobs.begin(), jobs.end(), job); it != jobs.end()) {
                jobs.erase(it);
                return jsonResponse(
                    503, {{"error", "the renderer did not answer in 30 s; nothing changed"}});
            }
        }
        return answer.get();
    };
    auto reply = [](httplib::Response& res, httplib::Response r) {
        res.status = r.status;
        res.body = std::move(r.body);
        for (auto& [k, v] : r.headers) res.set_header(k.c_str(), v);
    };

    httplib::Server server;
    // Bodies are small JSON objects: anything over 1 MiB is answered 413 unread.
    server.set_payload_max_length(1u << 20);
    // Idle keep-alive connections are closed after a second, so that a shutdown never waits
    // on one for longer.
    server.set_keep_alive_timeout(1);

    // Every request passes here first (Jupyter's rules for a local server):
    // - the Host header must name this server (no DNS rebinding), unless bound to every address;
    // - the token: `Authorization: Bearer TOKEN`, `?token=TOKEN`, or the cookie the page sets;
    // - the method must be the route's (405 with Allow);
    // - a POST must say `Content-Type: application/json`, and come from this server's own
    //   page when a browser sends it (an Origin header, if any, must be this server's).
    const std::map<std::string, std::string> routes = {
        {"/", "GET"},          {"/api/state", "GET"},  {"/api/graph", "GET"},
        {"/api/image", "GET"}, {"/api/param", "POST"}, {"/api/pass", "POST"}};
    int port = -1;
    auto ownHost = [&](const std::string& host) {
        if (options.host == "0.0.0.0" || options.host == "::") return true;
        const std::string p = ":" + std::to_string(port);
        for (const std::string& name : {options.host, std::string("127.0.0.1"),
                                        std::string("localhost"), std::string("[::1]")})
            if (host == name + p) return true;
        return false;
    };
    std::atomic<int64_t> lastRequest{0};  // steady-clock ms of the latest request's arrival
    auto nowMs = [] {
        return std::chrono::duration_cast<std::chrono::milliseconds>(
                   std::chrono::steady_clock::now().time_since_epoch())
            .count();
    };
    server.set_pre_routing_handler([&](const httplib::Request& req, httplib::Response& res) {
        lastRequest = nowMs();
        auto refuse = [&](int status, const std::string& message) {
            res.status = status;
            res.set_content(json{{"error", message}}.dump(), "application/json");
            return httplib::Server::HandlerResponse::Handled;
        };
        const std::string host = req.get_header_value("Host");
        if (!ownHost(host))
            return refuse(403, "Host " + quoted(host) + " is not this server's address");
        const std::string bearer = req.get_header_value("Authorization");
        const bool authorised =
            sameToken(req.get_param_value("token"), token) ||
            (bearer.rfind("Bearer ", 0) == 0 && sameToken(bearer.substr(7), token)) ||
            sameToken(cookie(req.get_header_value("Cookie"), "rgraph_token"), token);
        if (!authorised)
            return refuse(401,
                          "a token is needed: open the address rgraph serve printed "
                          "(…/?token=TOKEN), or send Authorization: Bearer TOKEN");
        auto route = routes.find(req.path);
        if (route == routes.end()) return refuse(404, "no such endpoint " + quoted(req.path));
        if (req.method != route->second && !(req.method == "HEAD" && route->second == "GET")) {
            res.set_header("Allow", route->second);
            return refuse(405, req.method + " is not allowed on " + req.path +
                                   " (allowed: " + route->second + ")");
        }
        if (req.method == "POST") {
            if (req.get_header_value("Content-Type").rfind("application/json", 0) != 0)
                return refuse(415, "a POST's body must be sent as Content-Type: application/json");
            const std::string origin = req.get_header_value("Origin");
            if (!origin.empty() && (origin.rfind("http://", 0) != 0 || !ownHost(origin.substr(7))))
                return refuse(403,
                              "Origin " + quoted(origin) +
                                  " is not this server: requests from other pages are refused");
        }
        // The page's later requests carry the token as a cookie only this server sees.
        if (req.path == "/" && req.has_param("token"))
            res.set_header("Set-Cookie",
                           "rgraph_token=" + token + "; Path=/; HttpOnly; SameSite=Strict");
        return httplib::Server::HandlerResponse::Unhandled;
    });

    server.Get("/", [](const httplib::Request&, httplib::Response& res) {
        res.set_content(kServePage, "text/html; charset=utf-8");
    });
    server.Get("/api/state", [&](const httplib::Request&, httplib::Response& res) {
        std::lock_guard lock(mutex);
        res.set_content(state.dump(), "application/json");
    });
    server.Get("/api/graph", [&](const httplib::Request&, httplib::Response& res) {
        reply(res, run([&] {
                  httplib::Response r;
                  r.set_content(runtime.executor().plan().toJson(), "application/json");
                  return r;
              }));
    });
    // {"name": "ec", "value": 1.5} / {"name": "fxaa", "enabled": false}: checked and applied on the
    // render thread through the path rg.frame's changes take; one the graph cannot be built with
    // is answered 400 with the compiler's reason, and nothing changes.
    server.Post("/api/param", [&](const httplib::Request& req, httplib::Response& res) {
        auto body = parseBody(req.body);
        if (!body) return reply(res, jsonResponse(400, {{"error", body.error().message}}));
        if (!body->is_object() || !body->contains("name") || !(*body)["name"].is_string() ||
            !body->contains("value"))
            return reply(
                res,
                jsonResponse(400, {{"error", "expected {\"name\": PARAM, \"value\": VALUE}"}}));
        const std::string name = (*body)["name"].get<std::string>();
        if (name.size() > 256)
            return reply(res, jsonResponse(400, {{"error", "name: longer than 256 characters"}}));
        auto value = jsonValue((*body)["value"]);
        if (!value) return reply(res, jsonResponse(400, {{"error", value.error().message}}));
        reply(res, run([&, name, v = *value] {
                  auto r = session.setOverride(name, v);
                  return r ? jsonResponse(200, {{"ok", true}})
                           : jsonResponse(400, {{"error", r.error().message}});
              }));
    });
    server.Post("/api/pass", [&](const httplib::Request& req, httplib::Response& res) {
        auto body = parseBody(req.body);
        if (!body) return reply(res, jsonResponse(400, {{"error", body.error().message}}));
        if (!body->is_object() || !body->contains("name") || !(*body)["name"].is_string() ||
            !body->contains("enabled") || !(*body)["enabled"].is_boolean())
            return reply(
                res, jsonResponse(
                         400, {{"error", "expected {\"name\": PASS, \"enabled\": true|false}"}}));
        const std::string name = (*body)["name"].get<std::string>();
        if (name.size() > 256)
            return reply(res, jsonResponse(400, {{"error", "name: longer than 256 characters"}}));
        reply(res, run([&, name, on = (*body)["enabled"].get<bool>()] {
                  auto r = session.setPassOverride(name, on);
                  return r ? jsonResponse(200, {{"ok", true}})
                           : jsonResponse(400, {{"error", r.error().message}});
              }));
    });
    // ?resource=NAME (a texture, or LAYOUT.CHANNEL / gbuffer.CHANNEL) &ev=STOPS &format=png|exr.
    // A texture the plan keeps transient is exported first (a reload of the same script, which
    // leaves everything as it was when the name is not the pipeline's).
    server.Get("/api/image", [&](const httplib::Request& req, httplib::Response& res) {
        const std::string name = req.get_param_value("resource"),
                          format = req.has_param("format") ? req.get_param_value("format") : "png";
        char* end = nullptr;
        const std::string evText = req.has_param("ev") ? req.get_param_value("ev") : "0";
        const float ev = std::strtof(evText.c_str(), &end);
        if (name.empty())
            return reply(res, jsonResponse(400, {{"error", "resource: give ?resource=NAME"}}));
        if (name.size() > 256)
            return reply(res,
                         jsonResponse(400, {{"error", "resource: longer than 256 characters"}}));
        if (end == evText.c_str() || *end || !std::isfinite(ev) || std::fabs(ev) > 64)
            return reply(
                res, jsonResponse(400, {{"error", "ev: expected a number of stops in -64..64"}}));
        if (format != "png" && format != "exr")
            return reply(res, jsonResponse(400, {{"error", "format: expected 'png' or 'exr'"}}));
        reply(
            res, run([&, name, format, ev]() -> httplib::Response {
                const bool channel = name.find('.') != std::string::npos &&
                                     !session.pipeline().graph.findResource(name);
                const ResourceDesc* desc = session.pipeline().graph.findResource(name);
                if (!channel && !desc)
                    return jsonResponse(
                        400, {{"error", "resource: the pipeline has no texture " + quoted(name)}});
                if (desc && desc->kind != ResourceKind::Texture)
                    return jsonResponse(400,
                                        {{"error", "resource: " + quoted(name) + " is a buffer"}});
                auto captured = [&] {
                    const auto& c = session.captures();
                    return std::find(c.begin(), c.end(), name) != c.end();
                };
                auto exported = [&] {
                    for (const PlanResource& pr : runtime.executor().plan().resources)
                        if (pr.name == name) return pr.exported || pr.imported || pr.persistent;
                    return false;
                };
                if (channel ? !captured() : !exported()) {
                    if (auto r = session.addCapture(name); !r)
                        return jsonResponse(400, {{"error", "resource: " + r.error().message}});
                    if (auto r = session.frame(); !r)
                        return jsonResponse(500, {{"error", r.error().describe()}});
                }
                // The export reloaded the pipeline: `desc` pointed into the one before.
                desc = session.pipeline().graph.findResource(name);
                Result<Image> img =
                    fail(ErrorCode::NotFound, "resource: no such channel capture " + quoted(name));
                Format fmt = desc ? desc->texture.format : Format::RGBA32F;
                if (channel) {
                    for (const auto& c : session.channelCaptures())
                        if (c.name == name) img = session.channelImage(c);
                } else {
                    img = runtime.executor().readback(name);
                    for (const PlanResource& pr : runtime.executor().plan().resources)
                        if (pr.name == name) fmt = pr.format;
                }
                if (!img) return jsonResponse(400, {{"error", img.error().describe()}});
                const fs::path tmp = fs::temp_directory_path() /
                                     ("rgraph_serve_" + std::to_string(::getpid()) + "." + format);
                static const char* rgba[] = {"R", "G", "B", "A"};
                const std::vector<std::string> names(rgba,
                                                     rgba + std::min<uint32_t>(img->channels, 4));
                Result<void> written =
                    format == "png" ? writePng(tmp.string(), displayImage(*img, fmt, ev, channel))
                                    : writeExr(tmp.string(), {{"", names, *img}});
                if (!written) return jsonResponse(500, {{"error", written.error().describe()}});
                httplib::Response r;
                r.set_content(readFile(tmp.string()),
                              format == "png" ? "image/png" : "image/x-exr");
                std::error_code ec;
                fs::remove(tmp, ec);
                return r;
            }));
    });

    port = options.port == 0
               ? server.bind_to_any_port(options.host)
               : (server.bind_to_port(options.host, options.port) ? options.port : -1);
    if (port < 0) {
        std::fprintf(stderr, "rgraph: serve: cannot listen on %s:%d (in use?)\n",
                     options.host.c_str(), options.port);
        return 1;
    }
    g_stop = false;
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    std::thread http([&] { server.listen_after_bind(); });
    std::printf("rgraph serve: http://%s:%d/?token=%s\n", options.host.c_str(), port,
                token.c_str());
    std::fflush(stdout);

    // The render loop: frames, jobs from the handlers, file changes as `watch` picks them up.
    if (auto r = session.frame(); !r)
        lastError = r.error().describe();  // the files a first frame brings in
    FileWatch watched;
    watched.changed(session.files());
    auto lastPoll = std::chrono::steady_clock::now();
    uint64_t loads = session.loads();
    int trimIn = 0;
    while (!g_stop) {
        std::deque<std::shared_ptr<Job>> due;
        {
            std::lock_guard lock(mutex);
            due.swap(jobs);
        }
        for (auto& job : due) job->answer.set_value(job->work());
        // A job may have reloaded (an image export): its new files are watched from now on, as
        // they are; a script saved while it ran was watched before and is seen as changed.
        if (!due.empty()) watched.add(session.files());
        if (std::chrono::steady_clock::now() - lastPoll >
            std::chrono::milliseconds(options.pollMs)) {
            lastPoll = std::chrono::steady_clock::now();
            if (watched.changed(session.files())) {
                if (auto r = session.load(options.pipeline); !r) {
                    lastError = r.error().describe();  // the previous plan keeps rendering
                    std::printf(
                        "rgraph serve: reload failed, the previous pipeline keeps running:\n%s\n",
                        lastError.c_str());
                } else {
                    lastError.clear();
                    std::printf("rgraph serve: reloaded %s\n", options.pipeline.c_str());
                }
                std::fflush(stdout);
                watched.add(session.files());
            }
        }
        // A few frames after a load (a reload, a capture's export) the previous plan's and
        // scene's memory is free (retired through the frames in flight); glibc keeps freed heap
        // pages, and a reload allocates the new plan beside the old, so without giving them back
        // a served process's RSS stays at its largest (~250 MiB over the steady state at 160x90).
        if (session.loads() != loads) {
            loads = session.loads();
            trimIn = 4;
        }
        if (trimIn && --trimIn == 0) malloc_trim(0);
        const auto t0 = std::chrono::steady_clock::now();
        std::string frameError;
        if (auto r = session.frame(); !r)
            frameError = r.error().describe();
        else if (auto f = runtime.executor().finish(); !f)
            frameError = f.error().describe();
        ++frames;
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        {
            json s = stateJson(runtime, session, frames,
                               frameError.empty() ? lastError : frameError, ms);
            std::lock_guard lock(mutex);
            state = std::move(s);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(options.frameIntervalMs));
    }
    // Shutdown: no job is taken from now on; those waiting are answered 503, and so is every
    // request that still arrives while the server keeps listening — until none has for 150 ms, at
    // most a second — so that connections already accepted are answered, not closed unread.
    // Then the server closes (idle keep-alive connections within a second).
    {
        std::lock_guard lock(mutex);
        stopping = true;
        for (auto& job : jobs)
            job->answer.set_value(jsonResponse(503, {{"error", "shutting down"}}));
        jobs.clear();
    }
    for (const int64_t start = nowMs(); nowMs() - start < 1000 && nowMs() - lastRequest < 150;)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    server.stop();
    http.join();
    if (auto f = runtime.executor().finish(); !f)
        std::fprintf(stderr, "rgraph: serve: the last frame: %s\n", f.error().describe().c_str());
    std::printf("rgraph serve: stopped after %llu frames\n",
                static_cast<unsigned long long>(frames));
    return 0;
}

}  // namespace rg
