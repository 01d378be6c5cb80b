// The workbench page: each step calls one route; /ws streams the run. Plain JS and SVG, nothing loaded from elsewhere.
"use strict";

const $ = (selector) => document.querySelector(selector);
const SVG = "http://www.w3.org/2000/svg";
const UNITS = { um: "µm", arcsec: "″", mm: "mm" };
const unit = (name) => UNITS[name] || name;
const fmt = (value, digits) => (value === null || value === undefined || !Number.isFinite(value) ? "—" : value.toFixed(digits));

const view = { plan: null, trace: { t: [], x: [] }, lastDraw: 0, runState: "idle", samples: 0, restoring: false,
  tests: [], test: null, plans: {}, machine: null, choices: [], runTest: null, runAxis: null };

// this tab's id, kept over a reload of the tab (not shared with another tab): the visit is held by one tab at a time
const TAB = sessionStorage.getItem("axiscal-tab") || `${Date.now().toString(36)}-${Math.random().toString(36).slice(2, 10)}`;
sessionStorage.setItem("axiscal-tab", TAB);

function readonly(on) {
  $("#readonly").hidden = !on;
  document.body.dataset.readonly = on ? "true" : "false";
}

// ---- navigation ---------------------------------------------------------------------------------
function show(step) {
  document.querySelectorAll("section[data-section]").forEach((s) => { s.hidden = s.dataset.section !== step; });
  document.querySelectorAll("nav button").forEach((b) => {
    if (b.dataset.step === step) b.setAttribute("aria-current", "page"); else b.removeAttribute("aria-current");
  });
  if (step === "machines") { loadMachines(); loadUnfinished(); }
  if (step === "connect") loadPorts();
  if (!view.restoring) call("POST", "/api/step", { step }).catch(() => {});  // opened here again after a reload
}
document.querySelectorAll("nav button").forEach((b) => b.addEventListener("click", () => show(b.dataset.step)));

// ---- calls --------------------------------------------------------------------------------------
async function call(method, url, body, raw) {
  const options = { method, headers: { "x-axiscal-tab": TAB } };
  if (body !== undefined) { options.headers["content-type"] = "application/json"; options.body = JSON.stringify(body); }
  if (raw !== undefined) { options.headers["content-type"] = "application/octet-stream"; options.body = raw; }
  const response = await fetch(url, options);
  const data = response.status === 413 ? { error: "the file is too large for the workbench (16 MiB at most)" } : await response.json();
  const error = $("#error");
  if (response.status === 409 && data.readonly) readonly(true);
  if (!response.ok) {
    error.textContent = data.fields ? "Please correct the fields marked." : data.error;
    error.hidden = false;
    const failure = new Error(data.error); failure.fields = data.fields; throw failure;
  }
  error.hidden = true;
  return data;
}

function formData(form) {
  const out = {};
  for (const element of form.elements) {
    if (!element.name) continue;
    if (element.type === "checkbox") { (out[element.name] = out[element.name] || []); if (element.checked) out[element.name].push(element.value); continue; }
    if (element.type === "number") { out[element.name] = element.value === "" ? null : Number(element.value); continue; }
    if (element.value !== "" || element.required) out[element.name] = element.value;
  }
  return out;
}

function fieldErrors(form, fields) {
  form.querySelectorAll(".field-error").forEach((span) => {
    const text = (fields || {})[span.dataset.for] || "";
    span.textContent = text;
    const input = form.elements[span.dataset.for];
    if (input && input.setAttribute) input.setAttribute("aria-invalid", text ? "true" : "false");
  });
}

async function submit(form, url, done) {
  try { const data = await call("POST", url, formData(form)); fieldErrors(form, {}); done(data); }
  catch (e) { fieldErrors(form, e.fields); }
}

// ---- drawing (numbers from the server, placed on the screen) ------------------------------------
function el(name, attrs, parent) {
  const node = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (parent) parent.appendChild(node);
  return node;
}

// round tick values (1, 2 or 5 times a power of ten), about five on an axis
function ticks(low, high) {
  const raw = (high - low) / 5, power = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * power).find((s) => s >= raw);
  const digits = Math.max(0, -Math.floor(Math.log10(step)));
  const out = [];
  for (let v = Math.ceil(low / step) * step; v <= high + step * 1e-9; v += step) out.push([v, v.toFixed(digits)]);
  return out;
}

function frame(svg, xs, ys, xlabel, ylabel) {
  svg.replaceChildren();
  const box = { left: 64, right: 606, top: 24, bottom: 226 };
  let [x0, x1] = [Math.min(...xs), Math.max(...xs)];
  let [y0, y1] = [Math.min(...ys), Math.max(...ys)];
  if (!(x1 > x0)) { x0 -= 1; x1 += 1; }
  if (!(y1 > y0)) { y0 -= 1; y1 += 1; }
  const pad = (y1 - y0) * 0.08; y0 -= pad; y1 += pad;
  const sx = (v) => box.left + ((v - x0) / (x1 - x0)) * (box.right - box.left);
  const sy = (v) => box.bottom - ((v - y0) / (y1 - y0)) * (box.bottom - box.top);
  el("rect", { x: box.left, y: box.top, width: box.right - box.left, height: box.bottom - box.top, class: "axes" }, svg);
  for (const [v, text] of ticks(y0, y1)) el("text", { x: box.left - 4, y: sy(v) + 4, class: "tick", "text-anchor": "end" }, svg).textContent = text;
  for (const [v, text] of ticks(x0, x1)) el("text", { x: sx(v), y: box.bottom + 14, class: "tick", "text-anchor": "middle" }, svg).textContent = text;
  el("text", { x: (box.left + box.right) / 2, y: 256, class: "label", "text-anchor": "middle" }, svg).textContent = xlabel;
  el("text", { x: 8, y: 13, class: "label" }, svg).textContent = ylabel;
  return { sx, sy, box };
}

function polyline(svg, points, cls) {
  if (points.length) el("polyline", { points: points.map(([a, b]) => `${a.toFixed(1)},${b.toFixed(1)}`).join(" "), class: cls }, svg);
}

function drawTrace(stops) {
  const svg = $("#trace"), { t, x } = view.trace;
  if (!t.length) { svg.replaceChildren(); return; }
  const plan = view.plans[view.runAxis] || view.plan, targets = plan ? plan.targets_mm : [];
  const { sx, sy } = frame(svg, [t[0], t[t.length - 1]], x.concat(targets), "time (s)", "reading (mm)");
  for (const target of targets) polyline(svg, [[sx(t[0]), sy(target)], [sx(t[t.length - 1]), sy(target)]], "target");
  // one point per pixel column (its lowest and highest sample): every sample is kept, the screen shows its envelope
  const columns = new Map();
  for (let i = 0; i < t.length; i++) {
    const c = Math.round(sx(t[i])), y = sy(x[i]), seen = columns.get(c);
    if (!seen) columns.set(c, [y, y]); else { seen[0] = Math.min(seen[0], y); seen[1] = Math.max(seen[1], y); }
  }
  const points = [];
  for (const [c, [lo, hi]] of columns) { points.push([c, lo]); if (hi !== lo) points.push([c, hi]); }
  polyline(svg, points, "reading");
  for (const s of stops) el("circle", { cx: sx(s.start_s), cy: sy(s.target_mm + s.deviation_um / 1000), r: 4, class: "stop" }, svg);
}

function drawDeviation(stops) {
  const svg = $("#deviation"), plan = view.plans[view.runAxis] || view.plan;
  const targets = plan ? plan.targets_mm : stops.map((s) => s.target_mm);
  if (!targets.length) { svg.replaceChildren(); return; }
  const { sx, sy } = frame(svg, targets, stops.length ? stops.map((s) => s.deviation_um) : [0], "target (mm)", "deviation (µm)");
  for (const s of stops) {
    el("circle", { cx: sx(s.target_mm) + (s.direction === "+" ? -3 : 3), cy: sy(s.deviation_um), r: 3.5, class: s.direction === "+" ? "up" : "down" }, svg);
  }
}

function drawCompensation(data) {
  const svg = $("#comp-plot"), x = data.targets_mm;
  const all = [...data.measured_um["+"], ...data.measured_um["-"], ...data.residual_um["+"], ...data.residual_um["-"]];
  const { sx, sy } = frame(svg, x, all, "target (mm)", "error (µm)");
  const series = [["measured_um", "+", "up"], ["measured_um", "-", "down"], ["residual_um", "+", "residual"], ["residual_um", "-", "residual"]];
  for (const [key, d, cls] of series) polyline(svg, x.map((v, i) => [sx(v), sy(data[key][d][i])]), cls);
}

function sparkline(values) {
  const svg = document.createElementNS(SVG, "svg");
  svg.setAttribute("viewBox", "0 0 120 28"); svg.setAttribute("class", "spark");
  if (values.length > 1) {
    const top = Math.max(1, ...values), sx = (i) => 4 + (112 * i) / (values.length - 1), sy = (v) => 24 - (20 * v) / top;
    el("line", { x1: 4, x2: 116, y1: sy(1), y2: sy(1), class: "limit" }, svg);
    polyline(svg, values.map((v, i) => [sx(i), sy(v)]), "reading");
  }
  return svg;
}

// ---- 1. machines ---------------------------------------------------------------------------------
async function loadMachines() {
  let rows;
  try { rows = await call("GET", "/api/machines"); } catch (e) { return; }
  const body = $("#machines tbody");
  body.replaceChildren();
  $("#machines-empty").hidden = rows.length > 0;
  for (const m of rows) {
    const tr = body.insertRow();
    for (const v of [m.machine, m.visits, m.last_date, m.verdict, m.next_due || "—"]) tr.insertCell().textContent = v;
    tr.cells[3].className = "verdict-" + m.verdict;
    const spark = tr.insertCell(); spark.appendChild(sparkline(m.spark));
    if (m.spark_figure) spark.title = m.spark_figure;
    const open = document.createElement("button"); open.textContent = "Open"; open.addEventListener("click", () => openMachine(m.machine));
    tr.insertCell().appendChild(open);
  }
}

async function loadUnfinished() {
  let rows;
  try { rows = await call("GET", "/api/visits"); } catch (e) { return; }
  const body = $("#unfinished tbody"); body.replaceChildren();
  $("#unfinished-block").hidden = rows.length === 0;
  for (const v of rows) {
    const tr = body.insertRow();
    const machine = v.serial ? `${v.machine} (${v.serial})` : v.machine;
    for (const c of [machine, v.date, v.title, v.problem || v.step]) tr.insertCell().textContent = c;
    const go = document.createElement("button"); go.textContent = "Continue";
    go.addEventListener("click", async () => { try { restore(await call("POST", "/api/visit/open", { folder: v.folder })); } catch (e) { /* shown */ } });
    if (v.problem) go.disabled = true;
    tr.insertCell().appendChild(go);
  }
}

async function openMachine(name) {
  const m = await call("GET", "/api/machine?name=" + encodeURIComponent(name));
  $("#machine-detail").hidden = false;
  $("#machine-title").textContent = m.machine;
  const body = $("#visits tbody"); body.replaceChildren();
  for (const v of m.visits) {
    const tr = body.insertRow();
    for (const c of [v.date, v.title, v.verdict, v.figures]) tr.insertCell().textContent = c;
    const cell = tr.insertCell();
    if (v.report) { const a = document.createElement("a"); a.href = "/files/" + v.report; a.target = "_blank"; a.textContent = "report"; cell.appendChild(a); }
  }
  const select = $("#trend-figure"); select.replaceChildren();
  for (const t of m.trends) { const o = document.createElement("option"); o.value = t.figure; o.textContent = `${t.figure} (${t.unit}), next due ${t.next_due}`; select.appendChild(o); }
  select.onchange = () => showTrend(m.machine, select.value);
  if (m.trends.length) showTrend(m.machine, m.trends[0].figure); else $("#trend-plot").textContent = "Three visits with a toleranced figure make a trend.";
}

async function showTrend(machine, figure) {
  const response = await fetch(`/api/trend?machine=${encodeURIComponent(machine)}&figure=${encodeURIComponent(figure)}`);
  $("#trend-plot").innerHTML = response.ok ? await response.text() : "";
}

// ---- 2. visit, 3. plan, 4. connect ----------------------------------------------------------------
$("#visit-form").elements.date.value = new Date().toISOString().slice(0, 10);
$("#visit-form").elements.issue_date.value = new Date().toISOString().slice(0, 10);
// the laboratory, the signatory and the next certificate number, as the last visit with a certificate left them
(async () => {
  try {
    const defaults = await call("GET", "/api/certificate");
    const form = $("#visit-form");
    for (const [name, value] of Object.entries(defaults)) if (form.elements[name] && !form.elements[name].value) form.elements[name].value = value;
    for (const name of ["location", "language"]) if (defaults[name]) form.elements[name].value = defaults[name];
  } catch (e) { /* no remembered laboratory */ }
  prefillBudget(false);
})();
// the uncertainty budget of the instrument's last visit: into an empty budget on a fresh form, over it when the instrument changes
async function prefillBudget(over) {
  const form = $("#visit-form"), note = $("#budget-from");
  const names = [...$("#budget-fields").querySelectorAll("input")].map((input) => input.name);
  let found;
  try {
    found = await call("GET", `/api/budget?instrument=${encodeURIComponent(form.elements.instrument.value)}&serial=${encodeURIComponent(form.elements.instrument_serial.value)}`);
  } catch (e) { return; }
  if (!found.fields || (!over && names.some((name) => form.elements[name].value !== ""))) { if (over) note.hidden = true; return; }
  for (const name of names) form.elements[name].value = found.fields[name] ?? "";
  form.elements.decision_rule.value = found.fields.decision_rule || "simple";
  note.textContent = `Prefilled from this instrument's last visit (${found.date}).`; note.hidden = false;
}
for (const name of ["instrument", "instrument_serial"]) $("#visit-form").elements[name].addEventListener("change", () => prefillBudget(true));
$("#visit-form").addEventListener("submit", (event) => {
  event.preventDefault();
  submit(event.target, "/api/visit", (data) => {
    $("#visit-saved").hidden = false;
    $("#visit-saved").textContent = `Written: ${data.campaign}`;
    $("#visit-name").textContent = data.folder;
    view.plan = null;
    view.machine = data.machine; view.plans = {}; view.test = null; view.chosen = data.machine.form;
    $("#plan-table tbody").replaceChildren(); $("#program").textContent = "";
    $("#file-block").hidden = false;
    showTests(data.tests); loadDataFiles(); loadMachineChoices();
  });
});

// ---- the visit's machine and its tests (tests.js) ----------------------------------------------------
initVisitTests();

$("#plan-form").addEventListener("submit", (event) => {
  event.preventDefault();
  submit(event.target, "/api/plan", showPlan);
});

function showPlan(data, shown) {
  view.plan = data;
  if (data.axis) view.plans[data.axis] = data;
  if (!shown) loadTests();  // the test is planned now
  $("#plan-readings").textContent = data.readings;
  const body = $("#plan-table tbody"); body.replaceChildren();
  for (const s of data.steps) { const tr = body.insertRow(); for (const v of [s.step, s.run, s.direction, fmt(s.target_mm, 4), fmt(s.move_to_mm, 4)]) tr.insertCell().textContent = v; }
  $("#program").textContent = data.program_text;
  const link = $("#program-download"); link.href = "/files/" + data.program + "?download=1"; link.hidden = false;
  link.textContent = "download " + data.program.split("/").pop();
}

function lights(states) {
  for (const name of ["instrument", "controller"]) {
    for (const id of ["#light-" + name, "#top-light-" + name]) { $(id).dataset.state = states[name]; $(id).setAttribute("aria-label", `${name} ${states[name]}`); }
    $("#state-" + name).textContent = states[name];
  }
}

function showTold(id, pairs) {
  const dl = $(id); dl.replaceChildren();
  for (const [name, value] of pairs || []) {
    const dt = document.createElement("dt"), dd = document.createElement("dd");
    dt.textContent = name; dd.textContent = value; dl.append(dt, dd);
  }
}

$("#connect-form").addEventListener("submit", async (event) => {
  event.preventDefault();
  const form = event.target;
  try {
    const c = await call("POST", "/api/connect", formData(form));
    fieldErrors(form, {});
    lights(c.lights);
    $("#live-reading").textContent = fmt(c.reading_mm, 6);
    $("#live-position").textContent = fmt(c.position_mm, 4);
    $("#connect-description").textContent = c.description;
    showTold("#told-instrument", c.told.instrument); showTold("#told-controller", c.told.controller);
    $("#refused").hidden = !c.refused; $("#refused").textContent = c.refused ? `The controller is not ready: ${c.refused}` : "";
  } catch (e) {
    fieldErrors(form, e.fields);
    lights({ instrument: "off", controller: "off" });
  }
});

// the computer's serial ports, listed when Connect opens and on request; a port clicked fills the instrument
async function loadPorts() {
  let ports;
  try { ports = await call("GET", "/api/ports"); } catch (e) { return; }
  $("#ports-count").textContent = ports.length;
  const body = $("#ports tbody"); body.replaceChildren();
  const specs = $("#instrument-specs"), controllers = $("#controller-specs");
  for (const list of [specs, controllers]) list.querySelectorAll("option[data-port]").forEach((o) => o.remove());
  for (const p of ports) {
    const tr = body.insertRow();
    for (const v of [p.device, p.description, p.vid ? `${p.vid}:${p.pid}` : "", p.serial_number || ""]) tr.insertCell().textContent = v;
    for (const kind of ["umd", "sylvac", "mahr", "touchdro"]) { const o = document.createElement("option"); o.value = `${kind}:${p.device}`; o.dataset.port = "1"; specs.appendChild(o); }
    for (const kind of ["grbl", "marlin"]) { const o = document.createElement("option"); o.value = `${kind}:${p.device}`; o.dataset.port = "1"; controllers.appendChild(o); }
  }
}
$("#ports-refresh").addEventListener("click", loadPorts);

// ---- 5. run ---------------------------------------------------------------------------------------
async function startRun(phase, resume, test, repeat) {
  view.trace = { t: [], x: [] };
  try { await call("POST", "/api/run", { phase, resume, test: test || view.test, repeat: Boolean(repeat) }); } catch (e) { /* shown in #error */ }
}
$("#start").addEventListener("click", () => startRun($("#phase").value, false));
$("#resume-broken").addEventListener("click", () => startRun($("#phase").value, true, view.runTest || view.test));
for (const action of ["pause", "resume", "abort"]) $("#" + action).addEventListener("click", () => call("POST", "/api/run/" + action).catch(() => {}));

function showRun(run) {
  // a run started, ended or of another test: the tests' states change with it
  if (run.state !== view.runState || (run.test || null) !== view.runTest) {
    view.runTest = run.test || null; view.runAxis = run.test ? run.test.split("-").pop() : view.runAxis;
    if (view.runState !== "idle" || run.state !== "idle") loadTests();
  }
  // a test that has just ended is evaluated at once: its figures wait in Results (and, as left, in Before / after)
  if (run.state === "done" && (view.runState === "running" || view.runState === "paused")) {
    const evaluated = showResults(run.phase).catch(() => {});
    if (run.phase === "as-left") evaluated.then(beforeAfter);
  }
  view.runState = run.state;
  $("#run-state").textContent = run.state;
  $("#run-state").dataset.state = run.state;
  $("#run-phase").textContent = run.phase ? `(${run.phase})` : "";
  $("#run-message").textContent = run.message || "";
  const active = run.state === "running" || run.state === "paused";
  $("#start").disabled = active;
  $("#pause").disabled = run.state !== "running";
  $("#resume").disabled = run.state !== "paused";
  $("#abort").disabled = !active;
  // a run ended short (connection lost, aborted, a step that could not be taken) goes on from its partial file
  $("#resume-broken").hidden = !run.resumable;
  if (run.state === "idle") return;
  lights(run.lights);
  $("#progress").textContent = `${run.taken} of ${run.total} stops`;
  $("#progress-bar").max = run.total || 1; $("#progress-bar").value = run.taken;
  const left = Math.round(run.remaining_s);
  $("#time-left").textContent = active ? `${Math.floor(left / 60)} min ${left % 60} s` : "—";
  $("#run-reading").textContent = fmt(run.reading_mm, 6);
  $("#run-position").textContent = fmt(run.position_mm, 4);
  $("#live-reading").textContent = fmt(run.reading_mm, 6);
  $("#live-position").textContent = fmt(run.position_mm, 4);
  const body = $("#stops tbody");
  const added = body.rows.length < run.stops.length;
  while (body.rows.length < run.stops.length) {
    const s = run.stops[body.rows.length], tr = body.insertRow();
    for (const v of [s.step, s.run, s.direction, fmt(s.target_mm, 4), fmt(s.deviation_um, 3), fmt(s.start_s, 2)]) tr.insertCell().textContent = v;
  }
  if (added) body.closest(".scroll").scrollTop = body.closest(".scroll").scrollHeight;  // the newest stop in view
  while (body.rows.length > run.stops.length) body.deleteRow(-1);
  drawTrace(run.stops);
  drawDeviation(run.stops);
}

function stream() {
  const socket = new WebSocket(`ws://${location.host}/ws?tab=${encodeURIComponent(TAB)}`);
  socket.onmessage = (event) => {
    const message = JSON.parse(event.data);
    if (message.reset) view.trace = { t: [], x: [] };
    const trace = message.trace;
    if (trace.from === view.trace.t.length) {
      for (let i = 0; i < trace.t_s.length; i++) { view.trace.t.push(trace.t_s[i]); view.trace.x.push(trace.reading_mm[i]); }
    }
    view.samples = view.trace.t.length;
    document.body.dataset.samples = view.samples;
    showRun(message.run);
  };
  socket.onclose = () => setTimeout(stream, 1000);
}
stream();

// ---- 6. results -----------------------------------------------------------------------------------
$("#show-results").addEventListener("click", () => showResults($("#results-phase").value));

async function showResults(phase) {
  $("#results-phase").value = phase;
  const data = await call("GET", "/api/results?phase=" + phase);
  const out = $("#results"); out.replaceChildren();
  const rule = document.createElement("p"); rule.id = "results-decision";
  rule.textContent = `${data.decision}. ` + (data.budget ? "U (k = 2) from the visit's uncertainty budget (budget.toml)."
    : "No uncertainty budget on the New visit form: U is not stated.");
  out.appendChild(rule);
  for (const test of data.tests) {
    const article = document.createElement("article"); article.className = "test"; article.id = "result-" + test.id;
    const named = view.tests.find((t) => t.id === test.id);
    const h = document.createElement("h3"); h.textContent = `${named ? named.label : test.id}: ${test.verdict.toUpperCase()}`; h.className = "verdict-" + test.verdict;
    article.appendChild(h);
    if (test.error) { const p = document.createElement("p"); p.className = "warn-line"; p.textContent = test.error; article.appendChild(p); out.appendChild(article); continue; }
    if (!test.checks.length && test.table && test.table.length) {  // not assessed (no tolerance): its figures as the report shows them
      const figures = document.createElement("table"); figures.className = "figures";
      for (const f of test.table) { const tr = figures.insertRow(); tr.insertCell().textContent = f.label; tr.insertCell().textContent = typeof f.value === "number" ? `${fmt(f.value, 3)} ${unit(f.unit)}` : `${f.value} ${unit(f.unit)}`; }
      article.appendChild(figures);
      for (const p of test.plots) { const div = document.createElement("div"); div.className = "plot"; div.innerHTML = p.svg; article.appendChild(div); }
      out.appendChild(article);
      continue;
    }
    const table = document.createElement("table"); table.className = "checks";
    table.createTHead().insertRow().append(...["Figure", "Value", "U (k=2)", "Tolerance", "Result"].map((t) => { const th = document.createElement("th"); th.textContent = t; return th; }));
    const body = table.createTBody();
    for (const c of test.checks) {
      const tr = body.insertRow();
      const u = unit(c.unit);
      for (const v of [c.figure, `${fmt(c.value, 2)} ${u}`, c.U === null ? "not stated" : `${fmt(c.U, 2)} ${u}`, `${fmt(c.limit, 2)} ${u}`, c.result]) tr.insertCell().textContent = v;
      tr.cells[4].className = "verdict-" + c.result;
    }
    article.appendChild(table);
    for (const p of test.plots) { const div = document.createElement("div"); div.className = "plot"; div.innerHTML = p.svg; article.appendChild(div); }
    out.appendChild(article);
  }
}

// ---- 7. compensate --------------------------------------------------------------------------------
$("#compensate").addEventListener("click", async () => showCompensation(await call("POST", "/api/compensate", { axis: $("#comp-axis").value || null })));

function showCompensation(data) {
  view.compensation = data;
  if (data.axis) $("#comp-axis").value = data.axis;
  $("#comp-description").textContent = `${data.description}; largest residual at the targets ${fmt(data.largest_residual_um, 2)} µm`;
  $("#comp-text").textContent = data.text;
  const link = $("#comp-download"); link.href = "/files/" + data.file + "?download=1"; link.hidden = false;
  link.textContent = "download " + data.file.split("/").pop();
  drawCompensation(data);
  $("#run-as-left").disabled = false;
}
$("#run-as-left").addEventListener("click", () => {
  $("#phase").value = "as-left"; show("run");
  startRun("as-left", false, `positioning-${view.compensation ? view.compensation.axis : $("#comp-axis").value}`);
});
// before / after: filled as soon as the as-left run has ended, or on request; while it is evaluated, or when it
// cannot be yet, the line beside the table says what it waits for
async function beforeAfter() {
  const status = $("#ba-status"), button = $("#before-after");
  status.textContent = "Evaluating the as-found and the as-left runs …"; status.dataset.state = "busy";
  button.disabled = true;
  try {
    const data = await call("GET", "/api/before-after");
    const body = $("#changes tbody"); body.replaceChildren();
    for (const c of data.changes) {
      const tr = body.insertRow();
      const u = unit(c.unit);
      for (const v of [c.test, c.figure, `${fmt(c.before, 2)} ${u}`, `${fmt(c.after, 2)} ${u}`, `${fmt(c.limit, 2)} ${u}`, c.result]) tr.insertCell().textContent = v;
    }
    const plots = $("#ba-plots"); plots.replaceChildren();
    for (const p of data.plots) { const div = document.createElement("div"); div.className = "plot"; div.innerHTML = p.svg; plots.appendChild(div); }
    status.textContent = `As found against as left: ${data.changes.length} figures.`; status.dataset.state = "done";
  } catch (e) {
    status.textContent = e.message; status.dataset.state = "waiting";
  } finally { button.disabled = false; }
}
$("#before-after").addEventListener("click", beforeAfter);

// ---- 8. finish ------------------------------------------------------------------------------------
$("#finish").addEventListener("click", async () => {
  $("#finish").disabled = true;
  try {
    showFinished(await call("POST", "/api/finish"));
  } finally { $("#finish").disabled = false; }
});

function showFinished(data) {
  const tests = data.tests ? ` over ${data.tests.length} tests (${data.tests.map((t) => `${t.id} ${t.verdict}`).join(", ")})` : "";
  $("#finish-verdict").textContent = `Verdict as found: ${data.verdict.toUpperCase()}${tests}. Stored in the history.`;
  const list = $("#report-links"); list.replaceChildren();
  for (const f of data.files) {
    const li = document.createElement("li"), a = document.createElement("a");
    a.href = "/files/" + f.path; a.textContent = `${f.phase} ${f.kind}: ${f.path}`; a.target = "_blank";
    li.appendChild(a); list.appendChild(li);
  }
}

// ---- the visit that was open: after a reload, a closed tab or a server restart, shown at the step it was at ----
function fill(form, values) {
  for (const [name, value] of Object.entries(values || {})) {
    const element = form.elements[name];
    if (!element || value === null || value === undefined) continue;
    if (element instanceof RadioNodeList || element.type === "checkbox") {
      const boxes = element instanceof RadioNodeList ? [...element] : [element];
      for (const box of boxes) box.checked = Array.isArray(value) && value.includes(box.value);
    } else element.value = value;
  }
}

function restore(state) {
  readonly(state.readonly);
  if (state.notice) { $("#error").textContent = state.notice; $("#error").hidden = false; }
  if (!state.open) { show("machines"); return; }
  view.restoring = true;
  $("#visit-name").textContent = state.folder;
  fill($("#visit-form"), state.visit);
  $("#visit-saved").hidden = false; $("#visit-saved").textContent = `Written: ${state.folder}/campaign.toml`;
  fill($("#plan-form"), state.plan_form);
  view.machine = state.machine; view.plans = state.plans || {};
  $("#file-block").hidden = false; loadDataFiles();
  if (state.plan) showPlan(state.plan, true); else { view.plan = null; $("#plan-table tbody").replaceChildren(); $("#program").textContent = ""; }
  if (state.plan) view.test = `positioning-${state.plan.axis}`;
  showTests(state.tests || []);
  view.chosen = state.machine ? state.machine.form : null; showChosen();
  fill($("#connect-form"), state.connection);
  if (state.connected) {
    lights(state.connected.lights); $("#connect-description").textContent = state.connected.description;
    showTold("#told-instrument", state.connected.told.instrument); showTold("#told-controller", state.connected.told.controller);
  }
  else lights({ instrument: "off", controller: "off" });
  $("#phase").value = state.phase;
  if (state.compensation) showCompensation(state.compensation);
  if (state.finished) showFinished(state.finished);
  if (state.runs["as-found"]) showResults(state.runs["as-left"] ? "as-left" : "as-found").catch(() => {});
  if (state.runs["as-left"]) beforeAfter();
  show(state.step);
  view.restoring = false;
}

call("GET", "/api/state").then(restore).catch(() => show("machines"));
