// Prints what the viewer of a report reads out below each run's image: its stages by name and its
// score lines, through the report's own copies of the viewer's modules (result_set.js,
// metric_readout.js) and its settings.json, as the browser would load them. One line a run: its
// id, its stage names, then its score lines, joined by " | ".
//
//   node read_out_runs.mjs REPORT_DIR
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const reportDir = path.resolve(process.argv[2]);
const module = (name) => import(pathToFileURL(path.join(reportDir, 'viewer', name)).href);
const { ResultSet } = await module('result_set.js');
const { metricReadout } = await module('metric_readout.js');
const settings = JSON.parse(fs.readFileSync(path.join(reportDir, 'viewer', 'settings.json'), 'utf8'));
const records = JSON.parse(fs.readFileSync(path.join(reportDir, settings.result_set, 'results.json'), 'utf8'));
const results = new ResultSet(records, settings);
for (const run of results.runs) {
  const lines = metricReadout(results.metricTable, run.scores, run.temporal).map((l) => l.text);
  console.log(`${run.id}: stages ${Object.keys(run.stages).join(', ')} | ${lines.join(' | ')}`);
}
