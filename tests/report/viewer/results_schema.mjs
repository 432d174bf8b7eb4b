// The results record's JSON Schema (experiments/results.schema.json) on the JavaScript side: Ajv
// validates the records the viewer reads (results.json, which report.py turns into the viewer's
// manifest) against the same file as the C++ writer's tests and report/results.py, so the
// three readers cannot drift apart. The schema is draft 2020-12, hence Ajv's Ajv2020 class (the
// default class is draft-07 and refuses the "$schema" line).
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import Ajv2020 from 'ajv/dist/2020.js';

export const SCHEMA_PATH = path.join(path.dirname(fileURLToPath(import.meta.url)), '..', '..', '..', 'experiments', 'results.schema.json');

// "path: what" for one Ajv error, the path written as results_schema.py writes it ($.frame_ms.median,
// $.images.debug[0]) and naming the property that a missing or unexpected key is.
function describe(error) {
  const where = '$' + error.instancePath.split('/').slice(1).map((key) => (/^\d+$/.test(key) ? `[${key}]` : `.${key}`)).join('');
  if (error.keyword === 'required') return `${where}: missing required '${error.params.missingProperty}'`;
  if (error.keyword === 'additionalProperties') return `${where}: unexpected '${error.params.additionalProperty}'`;
  return `${where}: ${error.message}`;
}

// A function from one record to its problems ("path: what"), empty when the record is valid.
// Strict mode: a keyword Ajv does not know, or a schema it would read loosely, fails here rather
// than being skipped silently; union types ("type": ["number", "null"]) are standard JSON Schema.
export function recordValidator(schemaPath = SCHEMA_PATH) {
  const schema = JSON.parse(fs.readFileSync(schemaPath, 'utf8'));
  const validate = new Ajv2020({ allErrors: true, strict: true, allowUnionTypes: true }).compile(schema);
  return (record) => (validate(record) ? [] : validate.errors.map(describe));
}

// The problems of every record of a results.json, each prefixed by the record's index.
export function resultsProblems(records, validateRecord = recordValidator()) {
  if (!Array.isArray(records)) return ['results.json: expected an array of records'];
  return records.flatMap((record, i) => validateRecord(record).map((p) => `record ${i}: ${p}`));
}
