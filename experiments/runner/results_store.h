#pragma once
// An experiment's output folder (DESIGN.md "Experiments and results"):
//   experiment.json   what ran: config name and hash, shard, run count, program version
//   runs/<id>.json    one record per finished run, each written atomically: the source of truth
//   images/<id>.exr|png, maps/<id>/, references/<key>.exr|png
//   results.json, results.csv   derived from the records, rewritten atomically after every run
// Killing the runner loses at most the run in progress; --resume skips runs that have a record.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hybridlab {

class ResultsStore {
public:
    explicit ResultsStore(std::filesystem::path dir);

    const std::filesystem::path& dir() const { return dir_; }
    std::filesystem::path runsDir() const { return dir_ / "runs"; }
    std::filesystem::path imagesDir() const { return dir_ / "images"; }
    std::filesystem::path mapsDir() const { return dir_ / "maps"; }
    std::filesystem::path referencesDir() const { return dir_ / "references"; }

    void createLayout() const;
    bool hasRecord(const std::string& id) const;
    void writeRecord(const nlohmann::json& record) const;
    // Every record, ordered by run index.
    std::vector<nlohmann::json> loadRecords() const;
    // results.json (an array of records) and results.csv (one row per record, nested fields
    // flattened to dotted column names).
    void writeResults(const std::vector<nlohmann::json>& records) const;

private:
    std::filesystem::path dir_;
};

// Adds "temporal_error" to every record on a camera path whose previous frame (in the same
// sequence: scene, path, resolution, technique label and parameters) is also recorded:
// mean |(T_k - T_(k-1)) - (R_k - R_(k-1))| over the display image, from the saved frames; and
// "temporal_error_masked", the same over the pixels either frame's reference mask selects (the
// reflective and refractive pixels), when both have one.
void addTemporalErrors(std::vector<nlohmann::json>& records, const std::filesystem::path& dir);

// results.csv's text for `records`.
std::string resultsCsv(const std::vector<nlohmann::json>& records);

}  // namespace hybridlab
