#include "experiments/runner/results_store.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <glm/common.hpp>

#include "common/core/atomic_file.h"
#include "common/core/directory_lock.h"
#include "common/core/io_error.h"
#include "common/image/image_io.h"
#include "metrics/temporal.h"

namespace hybridlab {
namespace fs = std::filesystem;
using nlohmann::json;

ResultsStore::ResultsStore(fs::path dir) : dir_(std::move(dir)) {}

void ResultsStore::createLayout() const {
    for (const auto& d : {runsDir(), imagesDir(), mapsDir(), referencesDir()}) createDirectories(d);
}

bool ResultsStore::hasRecord(const std::string& id) const { return fs::exists(runsDir() / (id + ".json")); }

void ResultsStore::writeRecord(const json& record) const {
    writeFileAtomically(runsDir() / (record.at("id").get<std::string>() + ".json"), record.dump(1) + "\n");
}

void ResultsStore::recordRun(const json& record) const { writeRecord(record); }

std::vector<json> ResultsStore::loadRecords() const {
    std::vector<json> records;
    if (!fs::exists(runsDir())) return records;
    for (const auto& e : fs::directory_iterator(runsDir())) {
        // Temporary files of an interrupted write start with a dot: not records.
        if (e.path().extension() != ".json" || e.path().filename().string().front() == '.') continue;
        std::ifstream in(e.path());
        records.push_back(json::parse(in));
    }
    std::sort(records.begin(), records.end(), [](const json& a, const json& b) { return a.at("index") < b.at("index"); });
    return records;
}

namespace {

void flatten(const json& j, const std::string& prefix, std::map<std::string, std::string>& out) {
    if (j.is_object()) {
        for (const auto& [k, v] : j.items()) flatten(v, prefix.empty() ? k : prefix + "." + k, out);
    } else if (j.is_string()) {
        out[prefix] = j.get<std::string>();
    } else if (j.is_null()) {
        out[prefix] = "";
    } else {
        out[prefix] = j.dump();
    }
}

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace

std::string resultsCsv(const std::vector<json>& records) {
    std::vector<std::map<std::string, std::string>> rows;
    std::set<std::string> columns;
    for (const auto& r : records) {
        std::map<std::string, std::string> row;
        flatten(r, "", row);
        for (const auto& [k, v] : row) columns.insert(k);
        rows.push_back(std::move(row));
    }
    // Identity first, then everything else alphabetically.
    const std::vector<std::string> leading = {"index", "id", "scene", "view", "frame", "width", "height", "technique", "label", "parameters_text"};
    std::vector<std::string> order;
    for (const auto& c : leading)
        if (columns.erase(c)) order.push_back(c);
    order.insert(order.end(), columns.begin(), columns.end());
    std::ostringstream out;
    for (std::size_t i = 0; i < order.size(); ++i) out << (i ? "," : "") << csvField(order[i]);
    out << "\n";
    for (const auto& row : rows) {
        for (std::size_t i = 0; i < order.size(); ++i) {
            auto it = row.find(order[i]);
            out << (i ? "," : "") << (it == row.end() ? "" : csvField(it->second));
        }
        out << "\n";
    }
    return out.str();
}

// results.json is written after results.csv and removed before it: while it exists, both are whole.
bool ResultsStore::hasResults() const { return fs::exists(dir_ / "results.json"); }

void ResultsStore::removeResults() const {
    for (const char* name : {"results.json", "results.csv"}) {
        std::error_code ec;
        fs::remove(dir_ / name, ec);
        if (ec) throw IoError::fromErrno(dir_ / name, "remove", ec.value());
    }
}

std::vector<json> ResultsStore::finalRecords(const json& experiment) const {
    std::vector<json> records = loadRecords();
    // Result sets older than the config's metric list all had the temporal error.
    const json metrics = experiment.value("metrics", json::array({"temporal"}));
    const bool temporal = std::find(metrics.begin(), metrics.end(), "temporal") != metrics.end();
    if (temporal && experiment.at("shard").at("count") == 1 && records.size() == experiment.at("runs_total").get<std::size_t>())
        addTemporalErrors(records, dir_);
    return records;
}

void ResultsStore::writeResults(const std::vector<json>& records) const {
    writeFileAtomically(dir_ / "results.csv", resultsCsv(records));
    writeFileAtomically(dir_ / "results.json", json(records).dump(1) + "\n");
}

std::optional<std::size_t> writeMissingResults(const fs::path& dir) {
    const ResultsStore store(dir);
    const fs::path meta = dir / "experiment.json";
    if (store.hasResults() || !fs::exists(meta)) return std::nullopt;
    const DirectoryLock lock(dir);
    if (store.hasResults()) return std::nullopt;  // a runner finished in between
    std::ifstream in(meta);
    const std::vector<json> records = store.finalRecords(json::parse(in));
    store.writeResults(records);
    return records.size();
}

void addTemporalErrors(std::vector<json>& records, const fs::path& dir) {
    std::map<std::string, std::vector<std::size_t>> sequences;
    for (std::size_t i = 0; i < records.size(); ++i)
        if (records[i].at("frame").get<int>() >= 0) sequences[records[i].at("sequence").get<std::string>()].push_back(i);
    for (auto& [key, members] : sequences) {
        std::sort(members.begin(), members.end(),
                  [&](std::size_t a, std::size_t b) { return records[a].at("frame").get<int>() < records[b].at("frame").get<int>(); });
        for (std::size_t k = 1; k < members.size(); ++k) {
            const json& prev = records[members[k - 1]];
            json& cur = records[members[k]];
            auto load = [&](const json& r, const char* which) { return readImage(dir / r.at(which).at("exr").get<std::string>()); };
            std::vector<Image> test = {load(prev, "images"), load(cur, "images")};
            std::vector<Image> ref = {load(prev, "reference"), load(cur, "reference")};
            cur["temporal_error"] = temporalError(test, ref).perFrame.at(0);
            cur["temporal_previous_frame"] = prev.at("frame");
            // Also on the masked pixels of either frame (the reflective and refractive ones), where
            // a technique's own popping is not diluted by the rest of the image.
            if (prev.at("reference").contains("mask") && cur.at("reference").contains("mask")) {
                Image region = readImage(dir / prev.at("reference").at("mask").get<std::string>());
                const Image other = readImage(dir / cur.at("reference").at("mask").get<std::string>());
                requireSameSize(region, "the previous frame's mask", other, "the frame's mask");
                for (int y = 0; y < region.height(); ++y)
                    for (int x = 0; x < region.width(); ++x) region.at(x, y) = glm::max(region.at(x, y), other.at(x, y));
                const PixelMask mask = PixelMask::fromImage(region);
                if (mask.count() > 0) cur["temporal_error_masked"] = temporalError(test, ref, &mask).perFrame.at(0);
            }
        }
    }
}

}  // namespace hybridlab
