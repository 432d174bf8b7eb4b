// A run's scores as the viewer reads them out below its image: every metric of the result set's
// metric table (experiment.json's, which the report passes on in settings.json) at its decimals,
// and the summarised ones again on the reflective and refractive pixels. A metric the run lacks
// (left out by its config, or added after the set was written) reads as a dash.

// The value of metric `m` (a row of the table) in a record's region, found at its field (a dotted
// path: "flip.mean"); null where absent.
export function metricValue(record, region, m) {
  let value = record.metrics && record.metrics[region];
  for (const part of m.field.split('.')) {
    if (value === null || typeof value !== 'object' || !(part in value)) return null;
    value = value[part];
  }
  return value ?? null;
}

// {whole: {key: value}, masked: {key: value} or null} of a record, for every metric of `table`.
export function scoresOf(record, table) {
  const region = (name) => Object.fromEntries(table.map((m) => [m.key, metricValue(record, name, m)]));
  return { whole: region('whole'), masked: record.metrics && record.metrics.masked ? region('masked') : null };
}

const cell = (v, digits) => (v === null || v === undefined ? '-' : v.toFixed(digits));

// The read-out's lines as text: [{ masked: false, text: 'SSIM 0.9812 · FLIP (LDR) 0.0412 · ...' },
// and, where the run has the reflective and refractive pixels, { masked: true, text: 'refl./refr.: ...' }].
export function metricReadout(table, scores, temporal) {
  const part = (m, values) => `${m.label} ${cell(values[m.key], m.digits)}`;
  let whole = table.map((m) => part(m, scores.whole)).join(' · ');
  if (temporal !== null && temporal !== undefined) whole += ` · temporal ${cell(temporal, 5)}`;
  const lines = [{ masked: false, text: whole }];
  if (scores.masked) {
    lines.push({ masked: true, text: 'refl./refr.: ' + table.filter((m) => m.summarised).map((m) => part(m, scores.masked)).join(' · ') });
  }
  return lines;
}
