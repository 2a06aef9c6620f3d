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
#include <thread>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "image/image.h"
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
            if (!e.is_number()) return fail(ErrorCode::InvalidInput, "value: a list holds numbers only");
            list.push_back(Value(e.get<double>()));
        }
        return Value(list);
    }
    return fail(ErrorCode::InvalidInput, "value: expected a number, a boolean, a string or a list of numbers");
}

// What the page shows of the running pipeline, gathered on the render thread after each frame.
json stateJson(Runtime& runtime, const Session& session, uint64_t frames, const std::string& error, double frameMs) {
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
        const bool kept = std::any_of(ex.plan().passes.begin(), ex.plan().passes.end(), [&](const PlanPass& q) { return q.name == d.name; });
        passes.push_back({{"name", d.name}, {"kind", d.kind}, {"enabled", d.enabled}, {"kept", kept},
                          {"gpuMs", gpu.count(d.name) ? json(gpu[d.name]) : json(nullptr)},
                          {"cpuMs", cpu.count(d.name) ? json(cpu[d.name]) : json(nullptr)}, {"origin", d.origin}});
    }
    state["passes"] = passes;
    json params = json::array();
    for (const ParamDesc& d : p.params) {
        json j{{"name", d.name}, {"type", paramTypeName(d.type)}, {"value", valueJson(d.value)}, {"doc", d.doc}};
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
    const bool linear = decoded || f.floating || f.depth || f.srgb;  // sRGB textures read back linear
    const float scale = std::exp2(ev);
    Image out(in.width, in.height, 3);
    for (size_t i = 0; i < size_t(in.width) * in.height; ++i)
        for (uint32_t c = 0; c < 3; ++c) {
            float v = in.pixels[i * in.channels + std::min(c, in.channels - 1)];
            if (in.channels == 2 && c == 2) v = 0.0f;
            if (std::isnan(v)) v = c == 1 ? 0.0f : 1.0f;
            out.pixels[i * 3 + c] = linear ? srgbEncode(std::clamp(v * scale, 0.0f, 1.0f)) : std::clamp(v, 0.0f, 1.0f);
        }
    return out;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

int serve(Runtime& runtime, Session& session, const ServeOptions& options) {
    // The render thread owns the session; HTTP handlers hand it jobs and wait for their answers.
    std::mutex mutex;
    std::deque<std::function<void()>> jobs;
    json state;
    std::string lastError;
    uint64_t frames = 0;

    auto run = [&](std::function<httplib::Response()> job) {
        auto task = std::make_shared<std::packaged_task<httplib::Response()>>(std::move(job));
        auto answer = task->get_future();
        {
            std::lock_guard lock(mutex);
            jobs.push_back([task] { (*task)(); });
        }
        if (answer.wait_for(std::chrono::seconds(30)) != std::future_status::ready) {
            httplib::Response r;
            r.status = 503;
            r.set_content(json{{"error", "the renderer did not answer in 30 s"}}.dump(), "application/json");
            return r;
        }
        return answer.get();
    };
    auto jsonResponse = [](int status, const json& body) {
        httplib::Response r;
        r.status = status;
        r.set_content(body.dump(), "application/json");
        return r;
    };
    auto reply = [](httplib::Response& res, httplib::Response r) {
        res.status = r.status;
        res.body = std::move(r.body);
        res.headers = std::move(r.headers);
    };

    httplib::Server server;
    server.Get("/", [](const httplib::Request&, httplib::Response& res) { res.set_content(kServePage, "text/html; charset=utf-8"); });
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
    // {"name": "ec", "value": 1.5} / {"pass": "fxaa", "enabled": false}: checked, applied from the
    // next frame through the same path as rg.frame's changes; a bad request changes nothing.
    server.Post("/api/param", [&](const httplib::Request& req, httplib::Response& res) {
        json body = json::parse(req.body, nullptr, false);
        if (body.is_discarded() || !body.is_object() || !body.contains("name") || !body["name"].is_string() || !body.contains("value"))
            return reply(res, jsonResponse(400, {{"error", "expected {\"name\": PARAM, \"value\": VALUE}"}}));
        auto value = jsonValue(body["value"]);
        if (!value) return reply(res, jsonResponse(400, {{"error", value.error().message}}));
        reply(res, run([&, name = body["name"].get<std::string>(), v = *value] {
            auto r = session.setOverride(name, v);
            return r ? jsonResponse(200, {{"ok", true}}) : jsonResponse(400, {{"error", r.error().message}});
        }));
    });
    server.Post("/api/pass", [&](const httplib::Request& req, httplib::Response& res) {
        json body = json::parse(req.body, nullptr, false);
        if (body.is_discarded() || !body.is_object() || !body.contains("name") || !body["name"].is_string() || !body.contains("enabled") ||
            !body["enabled"].is_boolean())
            return reply(res, jsonResponse(400, {{"error", "expected {\"name\": PASS, \"enabled\": true|false}"}}));
        reply(res, run([&, name = body["name"].get<std::string>(), on = body["enabled"].get<bool>()] {
            auto r = session.setPassOverride(name, on);
            return r ? jsonResponse(200, {{"ok", true}}) : jsonResponse(400, {{"error", r.error().message}});
        }));
    });
    // ?resource=NAME (a texture, or LAYOUT.CHANNEL / gbuffer.CHANNEL) &ev=STOPS &format=png|exr.
    // A texture the plan keeps transient is exported first (a reload of the same script).
    server.Get("/api/image", [&](const httplib::Request& req, httplib::Response& res) {
        const std::string name = req.get_param_value("resource"), format = req.has_param("format") ? req.get_param_value("format") : "png";
        char* end = nullptr;
        const std::string evText = req.has_param("ev") ? req.get_param_value("ev") : "0";
        const float ev = std::strtof(evText.c_str(), &end);
        if (name.empty()) return reply(res, jsonResponse(400, {{"error", "resource: give ?resource=NAME"}}));
        if (end == evText.c_str() || *end || !std::isfinite(ev) || std::fabs(ev) > 64)
            return reply(res, jsonResponse(400, {{"error", "ev: expected a number of stops in -64..64"}}));
        if (format != "png" && format != "exr") return reply(res, jsonResponse(400, {{"error", "format: expected 'png' or 'exr'"}}));
        reply(res, run([&, name, format, ev]() -> httplib::Response {
            const bool channel = name.find('.') != std::string::npos && !session.pipeline().graph.findResource(name);
            const ResourceDesc* desc = session.pipeline().graph.findResource(name);
            if (!channel && !desc) return jsonResponse(400, {{"error", "resource: the pipeline has no texture '" + name + "'"}});
            if (desc && desc->kind != ResourceKind::Texture) return jsonResponse(400, {{"error", "resource: '" + name + "' is a buffer"}});
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
                session.addCapture(name);
                if (auto r = session.load(session.pipeline().file); !r) return jsonResponse(400, {{"error", r.error().describe()}});
                if (auto r = session.frame(); !r) return jsonResponse(500, {{"error", r.error().describe()}});
            }
            Result<Image> img = fail(ErrorCode::NotFound, "resource: no such channel capture '" + name + "'");
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
            const fs::path tmp = fs::temp_directory_path() / ("rgraph_serve_" + std::to_string(::getpid()) + "." + format);
            static const char* rgba[] = {"R", "G", "B", "A"};
            const std::vector<std::string> names(rgba, rgba + std::min<uint32_t>(img->channels, 4));
            Result<void> written = format == "png" ? writePng(tmp.string(), displayImage(*img, fmt, ev, channel))
                                                   : writeExr(tmp.string(), {{"", names, *img}});
            if (!written) return jsonResponse(500, {{"error", written.error().describe()}});
            httplib::Response r;
            r.set_content(readFile(tmp.string()), format == "png" ? "image/png" : "image/x-exr");
            std::error_code ec;
            fs::remove(tmp, ec);
            return r;
        }));
    });

    const int port = options.port == 0 ? server.bind_to_any_port(options.host) : (server.bind_to_port(options.host, options.port) ? options.port : -1);
    if (port < 0) {
        std::fprintf(stderr, "rgraph: serve: cannot listen on %s:%d (in use?)\n", options.host.c_str(), options.port);
        return 1;
    }
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    std::thread http([&] { server.listen_after_bind(); });
    std::printf("rgraph serve: http://%s:%d/\n", options.host.c_str(), port);
    std::fflush(stdout);

    // The render loop: frames, jobs from the handlers, file changes as `watch` picks them up.
    auto stamp = [&] {
        std::map<std::string, fs::file_time_type> t;
        for (const auto& f : session.files()) {
            std::error_code ec;
            t[f] = fs::last_write_time(f, ec);
        }
        return t;
    };
    if (auto r = session.frame(); !r) lastError = r.error().describe();  // the files a first frame brings in
    auto files = stamp();
    auto lastPoll = std::chrono::steady_clock::now();
    while (!g_stop) {
        std::deque<std::function<void()>> due;
        {
            std::lock_guard lock(mutex);
            due.swap(jobs);
        }
        for (auto& job : due) job();
        if (!due.empty()) {
            // A job may have reloaded (an image export): its new files are watched from now, the
            // ones it no longer uses are dropped. Files watched before keep their old stamps, so a
            // script saved while the job ran (its HTTP answer goes out before this) is still
            // seen as changed at the next poll.
            auto now = stamp();
            std::erase_if(files, [&](const auto& e) { return !now.contains(e.first); });
            for (const auto& [f, t] : now) files.try_emplace(f, t);
        }
        if (std::chrono::steady_clock::now() - lastPoll > std::chrono::milliseconds(options.pollMs)) {
            lastPoll = std::chrono::steady_clock::now();
            auto now = stamp();
            if (now != files) {
                files = now;
                if (auto r = session.load(options.pipeline); !r) {
                    lastError = r.error().describe();  // the previous plan keeps rendering
                    std::printf("rgraph serve: reload failed, the previous pipeline keeps running:\n%s\n", lastError.c_str());
                } else {
                    lastError.clear();
                    std::printf("rgraph serve: reloaded %s\n", options.pipeline.c_str());
                }
                std::fflush(stdout);
            }
        }
        const auto t0 = std::chrono::steady_clock::now();
        std::string frameError;
        if (auto r = session.frame(); !r) frameError = r.error().describe();
        else if (auto f = runtime.executor().finish(); !f) frameError = f.error().describe();
        ++frames;
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        {
            json s = stateJson(runtime, session, frames, frameError.empty() ? lastError : frameError, ms);
            std::lock_guard lock(mutex);
            state = std::move(s);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(options.frameIntervalMs));
    }
    server.stop();
    http.join();
    // Jobs that arrived meanwhile get an answer rather than a hang.
    for (auto& job : jobs) job();
    std::printf("rgraph serve: stopped after %llu frames\n", static_cast<unsigned long long>(frames));
    return 0;
}

}  // namespace rg
