// Prints what the viewer of a report reads out below each run's image: the score lines of every
// run, through the report's own copies of the viewer's modules (result_set.js, metric_readout.js)
// and its settings.json, as the browser would load them. One line a run: its id, then its lines
// joined by " | ".
//
//   node read_out_scores.mjs REPORT_DIR
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
  console.log(`${run.id}: ${metricReadout(results.metricTable, run.scores, run.temporal).map((l) => l.text).join(' | ')}`);
}
