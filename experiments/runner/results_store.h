#pragma once
// An experiment's output folder (DESIGN.md "Experiments and results"):
//   experiment.json   what ran: config name and hash, shard, run count, program version
//   runs/<id>.json    one record per finished run, each written atomically: the source of truth
//   images/<id>.exr|png, maps/<id>/, references/<key>.exr|png
//   results.json, results.csv   every record, derived from runs/
// Recording a run writes its record file alone, so N runs cost O(N) writes; results.json and
// results.csv are written once, when the records are final: at the end of `run` (complete or not),
// by `merge`, and by `report` for a set whose runner was killed. `run` removes them before it adds
// a record, so that a results.json that exists lists every record in runs/. Killing the runner
// loses at most the run in progress; --resume skips runs that have a record.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/core/input_error.h"
#include "experiments/runner/run_record.h"

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
    void writeRecord(const RunRecord& record) const;
    // What the runner does when a run finishes: its record written, nothing else (O(1) a run).
    void recordRun(const RunRecord& record) const;
    // Every record, ordered by run index. Throws InputError naming the file of one that is not a
    // record (run_record.h), of one whose id is not its file's name, of a second record of a run
    // (both files), and naming runs/ where it is not a folder; IoError where it cannot be listed.
    // Every reader of a set's records (--resume, merge, report's rebuild) reads them here.
    std::vector<RunRecord> loadRecords() const;

    // Whether results.json exists (then results.csv does too, and both list every record).
    bool hasResults() const;
    // Removes results.json and results.csv: called before records are added.
    void removeResults() const;
    // results.json (an array of records) and results.csv (one row per record, nested fields
    // flattened to dotted column names).
    void writeResults(const std::vector<RunRecord>& records) const;
    // The records as results.json holds them, for the set described by `experiment` (its
    // experiment.json): every record, with temporal errors when the set is complete and unsharded
    // and its metrics hold "temporal" (they need each frame's predecessor, which another shard may
    // hold).
    std::vector<RunRecord> finalRecords(const nlohmann::json& experiment) const;

private:
    std::filesystem::path dir_;
};

// Refuses (InputError naming the file and the record) a record of the set in `dir` whose files are
// missing or are not images of the record's size, or lie outside the set: its images, debug
// images, reference and mask (headers read, pixels not decoded: a set's images are read whole
// once, not decoded), and its error maps' folder. For `merge`, which would otherwise join a set the
// report cannot read.
void checkRecordFiles(const std::filesystem::path& dir, const RunRecord& record);

// For a reader of the set in `dir` (`report`): when its runner was killed before writing
// results.json and results.csv, writes them from the records as the runner would have, holding
// the folder's lock (InputError naming the runner while one writes the folder). Returns the number
// of records written, or nothing when `dir` has results.json or is not an experiment folder.
std::optional<std::size_t> writeMissingResults(const std::filesystem::path& dir);

// A result set's JSON file (experiment.json): InputError naming it where it is not JSON.
nlohmann::json readSetJson(const std::filesystem::path& file);
// What reading `file`, JSON but not the experiment record `run` writes, failed with (`e`): bad input.
InputError notExperimentJson(const std::filesystem::path& file, const nlohmann::json::exception& e);

// Adds the temporal error to every record on a camera path whose previous frame (in the same
// sequence: scene, path, resolution, technique label and parameters) is also recorded:
// mean |(T_k - T_(k-1)) - (R_k - R_(k-1))| over the display image, from the saved frames; and
// the masked temporal error, the same over the pixels either frame's reference mask selects (the
// reflective and refractive pixels), when both have one.
void addTemporalErrors(std::vector<RunRecord>& records, const std::filesystem::path& dir);

// results.csv's text for `records`.
std::string resultsCsv(const std::vector<RunRecord>& records);

}  // namespace hybridlab
