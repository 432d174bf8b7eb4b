#include "experiments/runner/results_store.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <glm/common.hpp>

#include "common/core/atomic_file.h"
#include "common/core/directory_lock.h"
#include "common/core/input_error.h"
#include "common/core/input_file.h"
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

void ResultsStore::writeRecord(const RunRecord& record) const {
    writeFileAtomically(runsDir() / (record.id + ".json"), toJson(record).dump(1) + "\n");
}

void ResultsStore::recordRun(const RunRecord& record) const { writeRecord(record); }

std::vector<RunRecord> ResultsStore::loadRecords() const {
    const fs::path runs = runsDir();
    if (!inputFolderPresent(runs, "the folder of the set's records (runs/<id>.json)")) return {};
    std::vector<fs::path> files;
    std::error_code ec;
    for (fs::directory_iterator it(runs, ec), end; !ec && it != end; it.increment(ec)) {
        // Temporary files of an interrupted write start with a dot: not records.
        const fs::path& file = it->path();
        if (file.extension() == ".json" && file.filename().string().front() != '.') files.push_back(file);
    }
    if (ec) throw IoError::fromErrno(runs, "list the folder", ec.value());
    std::sort(files.begin(), files.end());  // so that a message names the same file every time
    std::vector<RunRecord> records;
    std::map<std::size_t, fs::path> fileOfIndex;
    for (const fs::path& file : files) {
        const std::string text = readInputFile(file, "a run's record");
        try {
            records.push_back(fromJson(json::parse(text)));
        } catch (const std::exception& error) {  // not JSON, or not a record
            throw InputError(file.string() + ": " + error.what());
        }
        // One file a run, named by its id: what --resume skips and merge joins by.
        const RunRecord& r = records.back();
        if (r.id != file.stem().string()) {
            const fs::path own = runs / (r.id + ".json");
            std::error_code unseen;
            throw InputError(file.string() + ": holds the record of run '" + r.id + "', expected the run its name says, '" +
                             file.stem().string() + "'" + (fs::exists(own, unseen) ? " (" + own.string() + " holds that run's record too)" : ""));
        }
        if (const auto [at, added] = fileOfIndex.emplace(r.index, file); !added) {
            throw InputError(file.string() + ": records run " + std::to_string(r.index) + " of the plan, as " + at->second.string() +
                             " does; expected one record a run");
        }
    }
    std::sort(records.begin(), records.end(), [](const RunRecord& a, const RunRecord& b) { return a.index < b.index; });
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

std::string resultsCsv(const std::vector<RunRecord>& records) {
    std::vector<std::map<std::string, std::string>> rows;
    std::set<std::string> columns;
    for (const auto& r : records) {
        std::map<std::string, std::string> row;
        flatten(toJson(r), "", row);
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

std::vector<RunRecord> ResultsStore::finalRecords(const json& experiment) const {
    std::vector<RunRecord> records = loadRecords();
    // Result sets older than the config's metric list all had the temporal error.
    const json metrics = experiment.value("metrics", json::array({"temporal"}));
    const bool temporal = std::find(metrics.begin(), metrics.end(), "temporal") != metrics.end();
    if (temporal && experiment.at("shard").at("count") == 1 && records.size() == experiment.at("runs_total").get<std::size_t>())
        addTemporalErrors(records, dir_);
    return records;
}

void ResultsStore::writeResults(const std::vector<RunRecord>& records) const {
    writeFileAtomically(dir_ / "results.csv", resultsCsv(records));
    json all = json::array();
    for (const RunRecord& r : records) all.push_back(toJson(r));
    writeFileAtomically(dir_ / "results.json", all.dump(1) + "\n");
}

std::optional<std::size_t> writeMissingResults(const fs::path& dir) {
    const ResultsStore store(dir);
    const fs::path meta = dir / "experiment.json";
    if (store.hasResults() || !fs::exists(meta)) return std::nullopt;
    const DirectoryLock lock(dir);
    if (store.hasResults()) return std::nullopt;  // a runner finished in between
    std::vector<RunRecord> records;
    try {
        records = store.finalRecords(readSetJson(meta));
    } catch (const json::exception& e) {
        throw notExperimentJson(meta, e);
    }
    store.writeResults(records);
    return records.size();
}

void checkRecordFiles(const fs::path& dir, const RunRecord& record) {
    const fs::path recordFile = ResultsStore(dir).runsDir() / (record.id + ".json");
    const auto refuse = [&](const fs::path& file, const std::string& what) {
        return InputError(file.string() + ": " + what + " (named by " + recordFile.string() + ")");
    };
    // A reader's refusal of `file`, which starts with the file, with the record that names it.
    const auto named = [&](const fs::path& file, const InputError& e) {
        const std::string what = e.what();
        return refuse(file, what.rfind(file.string() + ": ", 0) == 0 ? what.substr(file.string().size() + 2) : what);
    };
    // A path the record names, relative to the set and inside it.
    const auto inSet = [&](const std::string& field, const std::string& name) {
        const fs::path relative(name);
        if (relative.empty() || relative.is_absolute() ||
            std::any_of(relative.begin(), relative.end(), [](const fs::path& part) { return part == ".."; }))
            throw InputError(recordFile.string() + ": " + field + ": expected a path inside the result set, got '" + name + "'");
        return dir / relative;
    };
    const auto image = [&](const std::string& field, const std::string& name, bool ofRecordSize) {
        const fs::path file = inSet(field, name);
        ImageSize size;
        try {
            size = checkImageFile(file);
        } catch (const InputError& e) {
            throw named(file, e);
        }
        if (ofRecordSize && (size.width != record.width || size.height != record.height))
            throw refuse(file, "is " + std::to_string(size.width) + "x" + std::to_string(size.height) + ", expected the run's " +
                                   std::to_string(record.width) + "x" + std::to_string(record.height));
    };
    image("images.exr", record.images.exr, true);
    image("images.png", record.images.png, true);
    for (const auto& [name, file] : record.images.debug) image("images.debug." + name, file, false);
    image("reference.exr", record.reference.exr, true);
    image("reference.png", record.reference.png, true);
    if (record.reference.mask) image("reference.mask", *record.reference.mask, true);
    if (record.images.maps) {
        const fs::path maps = inSet("images.maps", *record.images.maps);
        bool present = false;
        try {
            present = inputFolderPresent(maps, "the run's error maps");
        } catch (const InputError& e) {
            throw named(maps, e);
        }
        if (!present) throw refuse(maps, "folder not found, expected the run's error maps");
    }
}

InputError notExperimentJson(const fs::path& file, const json::exception& e) {
    return InputError(file.string() + ": not an experiment.json of hybridlab run (" + e.what() + ")");
}

json readSetJson(const fs::path& file) {
    const std::string text = readInputFile(file, "a result set's JSON file");
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        throw InputError(file.string() + ": " + e.what());
    }
}

void addTemporalErrors(std::vector<RunRecord>& records, const fs::path& dir) {
    std::map<std::string, std::vector<std::size_t>> sequences;
    for (std::size_t i = 0; i < records.size(); ++i)
        if (records[i].frame >= 0) sequences[records[i].sequence].push_back(i);
    for (auto& [key, members] : sequences) {
        std::sort(members.begin(), members.end(), [&](std::size_t a, std::size_t b) { return records[a].frame < records[b].frame; });
        for (std::size_t k = 1; k < members.size(); ++k) {
            const RunRecord& prev = records[members[k - 1]];
            RunRecord& cur = records[members[k]];
            const auto load = [&](const std::string& file) { return readImage(dir / file); };
            std::vector<Image> test = {load(prev.images.exr), load(cur.images.exr)};
            std::vector<Image> ref = {load(prev.reference.exr), load(cur.reference.exr)};
            cur.temporalError = temporalError(test, ref).perFrame.at(0);
            cur.temporalPreviousFrame = prev.frame;
            // Also on the masked pixels of either frame (the reflective and refractive ones), where
            // a technique's own popping is not diluted by the rest of the image.
            if (prev.reference.mask && cur.reference.mask) {
                Image region = readImage(dir / *prev.reference.mask);
                const Image other = readImage(dir / *cur.reference.mask);
                requireSameSize(region, "the previous frame's mask", other, "the frame's mask");
                for (int y = 0; y < region.height(); ++y)
                    for (int x = 0; x < region.width(); ++x) region.at(x, y) = glm::max(region.at(x, y), other.at(x, y));
                const PixelMask mask = PixelMask::fromImage(region);
                if (mask.count() > 0) cur.temporalErrorMasked = temporalError(test, ref, &mask).perFrame.at(0);
            }
        }
    }
}

}  // namespace hybridlab
