// The workbench page: the visit's machine, its tests and their states, the tests taken from files.
// Loaded before app.js, whose helpers ($, call, fill, formData, fieldErrors, view, showPlan, startRun ...) it uses
// once the page runs; app.js calls initVisitTests() once.
"use strict";

// a call whose answer only refreshes what is shown: it leaves the line of the last mistake as it is
async function quiet(url) {
  const response = await fetch(url, { headers: { "x-axiscal-tab": TAB } });
  if (!response.ok) throw new Error(url);
  return response.json();
}

async function loadMachineChoices() {
  try { view.choices = await quiet("/api/machine-choices"); } catch (e) { return; }
  const select = $("#machine-choice"), keep = select.value;
  select.replaceChildren();
  for (const m of [...view.choices, { choice: "new", label: "a new machine: chain and travels" }]) {
    const o = document.createElement("option"); o.value = m.choice; o.textContent = m.problem ? `${m.label}: ${m.problem}` : m.label;
    o.disabled = Boolean(m.problem); select.appendChild(o);
  }
  if ([...select.options].some((o) => o.value === keep)) select.value = keep;
  machineChosen();
  showChosen();
}

// the machine and the tests the open visit was written with, shown again on its form (after a reload)
function showChosen() {
  const chosen = view.chosen, select = $("#machine-choice"), form = $("#visit-form");
  if (!chosen) return;
  if ([...select.options].some((o) => o.value === chosen.machine_choice)) select.value = chosen.machine_choice;
  for (const name of ["machine_chain", "machine_travels"]) if (chosen[name]) form.elements[name].value = chosen[name];
  machineChosen();
  if (Array.isArray(chosen.tests)) form.querySelectorAll("#test-boxes input").forEach((box) => { box.checked = chosen.tests.includes(box.value); });
}

// the axes of the machine chosen (of the chain typed, for a new one): one box for the positioning of each
function chosenAxes() {
  if ($("#machine-choice").value === "new") {
    const chain = ($("#visit-form").elements.machine_chain.value || "").toUpperCase();
    return [...new Set(chain)].filter((c) => "XYZABC".includes(c)).map((axis) => ({ axis, rotary: "ABC".includes(axis) }));
  }
  const chosen = (view.choices || []).find((c) => c.choice === $("#machine-choice").value);
  return chosen ? chosen.axes : ["X", "Y", "Z"].map((axis) => ({ axis, rotary: false }));
}

function machineChosen() {
  const isNew = $("#machine-choice").value === "new";
  document.querySelectorAll("[data-new-machine]").forEach((label) => { label.hidden = !isNew; });
  const boxes = $("#test-boxes"), was = new Map([...boxes.querySelectorAll("input")].map((b) => [b.value, b.checked]));
  boxes.replaceChildren();
  for (const a of chosenAxes()) {
    const label = document.createElement("label"), box = document.createElement("input"), id = `positioning-${a.axis}`;
    box.type = "checkbox"; box.name = "tests"; box.value = id; box.checked = was.has(id) ? was.get(id) : true;
    label.className = "check";
    label.append(box, a.rotary ? ` Rotary positioning of ${a.axis} (its run from a file)` : ` Positioning of ${a.axis}`);
    boxes.appendChild(label);
  }
}

async function loadTests() {
  try { showTests(await quiet("/api/tests")); } catch (e) { /* no visit open */ }
}

// the visit's tests, each with its state, in each step's list; the test chosen is the one Plan and Run work on
function showTests(tests) {
  if (tests) view.tests = tests;
  if (!view.tests.some((t) => t.id === view.test)) {
    const first = view.tests.find((t) => t.source === "run") || view.tests[0];
    view.test = first ? first.id : null;
  }
  document.querySelectorAll(".tests-list").forEach((div) => renderTests(div, div.dataset.mode));
  selectTest(view.test, false);
  const select = $("#comp-axis"), keep = select.value;
  select.replaceChildren();
  for (const t of view.tests.filter((t) => t.source === "run" && t.state === "done")) {
    const o = document.createElement("option"); o.value = t.axis; o.textContent = t.axis; select.appendChild(o);
  }
  if ([...select.options].some((o) => o.value === keep)) select.value = keep;
}

function renderTests(div, mode) {
  div.replaceChildren();
  if (!view.tests.length) return;
  const table = document.createElement("table"); table.className = "tests";
  table.createTHead().insertRow().append(...["Test", "Data", "State", ""].map((text) => { const th = document.createElement("th"); th.textContent = text; return th; }));
  const body = table.createTBody();
  // Plan and Run list the tests run here; the tests from files are counted below them
  const listed = mode === "plan" || mode === "run" ? view.tests.filter((t) => t.source === "run") : view.tests;
  for (const t of listed) {
    const tr = body.insertRow(); tr.dataset.test = t.id;
    tr.classList.toggle("current", t.id === view.test && mode !== "visit" && mode !== "results");
    tr.insertCell().textContent = t.label;
    tr.insertCell().textContent = t.source === "run" ? (t.planned ? "run here (planned)" : "run here") : (t.files.length ? t.files.join(", ") : "from a file");
    const state = tr.insertCell(); state.className = "state"; state.dataset.state = t.state;
    state.textContent = t.message ? `${t.state}: ${t.message}` : t.state;
    const cell = tr.insertCell(), actions = [];
    if (mode === "plan" && t.source === "run") actions.push(["Plan", () => selectTest(t.id, true)]);
    if (mode === "run" && t.source === "run") {
      // a run ended short goes on from its last stop, or starts again from its first
      if (t.resumable) actions.push(["Resume", () => { selectTest(t.id, true); startRun("as-found", true, t.id); }]);
      actions.push([t.state === "planned" ? "Run" : "Repeat", () => { selectTest(t.id, true); startRun("as-found", false, t.id, t.state !== "planned"); }]);
    }
    if (mode === "results" && t.state === "done") actions.push(["Show", () => { const a = document.getElementById("result-" + t.id); if (a) a.scrollIntoView(); }]);
    if (mode === "visit" && t.source === "file" && t.files.length) actions.push(["Remove", () => removeTest(t.id)]);
    for (const [text, act] of actions) {
      const button = document.createElement("button"); button.type = "button"; button.textContent = text;
      button.disabled = t.state === "running"; button.addEventListener("click", act); cell.appendChild(button);
    }
  }
  div.appendChild(table);
  const others = view.tests.length - listed.length;
  if (others) {
    const note = document.createElement("p"); note.className = "muted small";
    const done = view.tests.filter((t) => t.source !== "run" && t.state === "done").length;
    note.textContent = `and ${others} test${others > 1 ? "s" : ""} from files (${done} with their data: New visit lists them)`;
    div.appendChild(note);
  }
}

function selectTest(id, chosen) {
  view.test = id;
  document.querySelectorAll(".tests-list[data-mode=plan] tr[data-test], .tests-list[data-mode=run] tr[data-test]")
    .forEach((tr) => tr.classList.toggle("current", tr.dataset.test === id));
  const t = view.tests.find((x) => x.id === id);
  for (const where of ["#plan-test", "#run-test"]) $(where).textContent = t ? `· ${t.label}` : "";
  if (!t || t.source !== "run") return;
  const form = $("#plan-form"), axis = ((view.machine || {}).axes || []).find((a) => a.axis === t.axis);
  form.elements.axis.value = t.axis;
  $("#plan-travel").textContent = axis ? `travel of ${t.axis}: ${axis.start} to ${axis.end} mm` : "";
  const planned = view.plans[t.axis];
  if (planned) { fill(form, planned.form); showPlan(planned, true); }
  else if (chosen) { view.plan = null; $("#plan-table tbody").replaceChildren(); $("#program").textContent = ""; $("#plan-readings").textContent = "0"; $("#program-download").hidden = true; }
}

async function removeTest(id) {
  try { showTests((await call("POST", "/api/tests/remove", { test: id })).tests); } catch (e) { /* shown */ }
}

// tests from files: a file of the data folder, or one uploaded into the visit's files/
async function loadDataFiles() {
  let files;
  try { files = await quiet("/api/data-files"); } catch (e) { return; }
  const list = $("#data-files"); list.replaceChildren();
  for (const f of files) { const o = document.createElement("option"); o.value = f; list.appendChild(o); }
}

// the tolerance a test from a file may state, in the unit it reports (added.py's tolerance_of): none for an .rtx capture
const TOLERANCE_OF = { straightness: ["um", "of the straightness"], squareness: ["arcsec", "of the squareness"],
  diagonal: ["um", "of the diagonal's error"], ballbar: ["um", "of the circular deviation G"] };

function fileKind() {
  const form = $("#file-form"), kind = $("#file-kind").value;
  form.querySelectorAll("[data-kinds]").forEach((label) => { label.hidden = !label.dataset.kinds.split(" ").includes(kind); });
  const rotary = "ABC".includes((form.elements.axis.value || "X").toUpperCase());
  const [unit, what] = kind === "positioning" || kind === "columnmap" ? [rotary ? "arcsec" : "um", "of E"] : TOLERANCE_OF[kind] || [];
  form.querySelectorAll("[data-tolerance]").forEach((label) => {
    label.hidden = label.dataset.tolerance !== unit;
    if (label.hidden) label.querySelector("input").value = "";  // a hidden tolerance is not sent
    label.querySelector(".tolerance-of").textContent = what || "";
  });
}

// the listeners of the New visit form's machine and tests, and of Tests from files (app.js calls it once)
function initVisitTests() {
  $("#machine-choice").addEventListener("change", machineChosen);
  $("#visit-form").elements.machine_chain.addEventListener("input", machineChosen);
  loadMachineChoices();
  $("#file-kind").addEventListener("change", fileKind);
  $("#file-form").elements.axis.addEventListener("input", fileKind);
  fileKind();
  $("#file-form").querySelectorAll("input[data-upload]").forEach((input) => input.addEventListener("change", async () => {
    const file = input.files[0], note = $("#file-added");
    if (!file) return;
    try {
      const stored = await call("POST", `/api/upload?name=${encodeURIComponent(file.name)}`, undefined, await file.arrayBuffer());
      $("#file-form").elements[input.dataset.upload].value = stored.file;
      note.className = "ok"; note.textContent = `Uploaded: ${stored.file}`;
      loadDataFiles();
    } catch (e) { note.className = "warn-line"; note.textContent = e.message; }
  }));
  $("#file-form").addEventListener("submit", async (event) => {
    event.preventDefault();
    const form = event.target, note = $("#file-added");
    note.textContent = "Checking the file …"; note.className = "muted";
    try {
      const data = await call("POST", "/api/tests/add", formData(form));
      fieldErrors(form, {});
      showTests(data.tests);
      const added = data.tests.find((t) => t.id === data.added);
      note.className = "ok"; note.textContent = `Added and checked: ${added ? added.label : data.added}`;
    } catch (e) {
      fieldErrors(form, e.fields);
      note.className = "warn-line"; note.textContent = e.fields ? "Please correct the fields marked." : e.message;
    }
  });
}
