// The live dashboard: takes the newest state from /ws and draws it (plot.js does the charts).
"use strict";

const COLORS = { ex_um: "#d62728", ey_um: "#2ca02c", ez_um: "#1f77b4", e_um: "#1d2430" };
const LABELS = { ex_um: "ex", ey_um: "ey", ez_um: "ez", e_um: "|e|" };
const ROTATION_AXIS = { A: "X", B: "Y", C: "Z" };
// A good frame older than this (stream time) makes the functional point's values stale.
const STALE_S = 0.5;
const DIGITS = { t_s: 4, px_mm: 4, py_mm: 4, pz_mm: 4, ex_um: 3, ey_um: 3, ez_um: 3, e_um: 3 };

let built = "";
let pending = null;

function $(id) { return document.getElementById(id); }

function setText(id, text) {
  const el = $(id);
  if (el && el.textContent !== text) el.textContent = text;
}

// What an ISO 230-1 error motion of an axis is: "EXX" positioning, "EYX" straightness, "EAX" roll,
// "EBX" pitch, "ECX" yaw (horizontal axes: rotation about vertical Z is yaw); a vertical Z axis tilts.
function errorKind(stem, letter) {
  const direction = stem[1];
  if (direction in ROTATION_AXIS) {
    const about = ROTATION_AXIS[direction];
    if (about === letter) return "roll";
    if (letter === "Z") return `tilt about ${about}`;
    return about === "Z" ? "yaw" : "pitch";
  }
  return direction === letter ? "positioning" : "straightness";
}

function limit(value) {
  return value === null || value === undefined ? "-" : String(Number(Number(value).toFixed(3)));
}

function show(value, digits) {
  return value === null || value === undefined ? "-" : Number(value).toFixed(digits);
}

// Axis panels are built once the axes are known: six charts per axis.
function buildAxes(state) {
  const key = Object.keys(state.axes).join(",");
  if (key === built) return;
  built = key;
  const holder = $("axes");
  holder.textContent = "";
  for (const letter of Object.keys(state.axes)) {
    const section = document.createElement("section");
    section.className = "card wide";
    section.innerHTML = `<h2>Axis ${letter}: six errors against position</h2><div class="axis-grid"></div>`;
    const grid = section.querySelector(".axis-grid");
    for (const name of Object.keys(state.axes[letter].errors)) {
      const canvas = document.createElement("canvas");
      canvas.className = "chart";
      canvas.width = 420;
      canvas.height = 190;
      canvas.id = "profile-" + name;
      grid.appendChild(canvas);
    }
    holder.appendChild(section);
  }
}

function drawAxes(state) {
  for (const [letter, axis] of Object.entries(state.axes)) {
    for (const [name, values] of Object.entries(axis.errors)) {
      const unit = name.endsWith("_urad") ? "\u00b5rad" : "\u00b5m";
      const stem = name.split("_")[0];
      drawChart($("profile-" + name), axis.position_mm, [{ values: values, color: "#1f77b4" }], {
        title: `${stem} (${errorKind(stem, letter)}, ${unit})`,
        xlabel: `${letter} position (mm)`,
        xrange: axis.travel_mm,  // the whole travel, ends included
      });
    }
  }
}

function drawHistory(state) {
  const names = Object.keys(COLORS);
  drawChart($("history"), state.history.t_s,
    names.map(n => ({ values: state.history[n], color: COLORS[n] })),
    { xlabel: "t (s)", ylabel: "\u00b5m" });
  const legend = $("history-legend");
  if (!legend.childElementCount) {
    for (const n of names) {
      const item = document.createElement("span");
      item.innerHTML = `<i style="background:${COLORS[n]}"></i>${LABELS[n]}`;
      legend.appendChild(item);
    }
  }
}

function drawLatest(state) {
  const latest = state.latest || {};
  for (const name of Object.keys(DIGITS)) {
    const el = $("v-" + name);
    const value = latest[name];
    el.dataset.value = value === null || value === undefined ? "" : String(value);
    setText("v-" + name, show(value, DIGITS[name]));
  }
  const positions = Object.keys(state.axes).map(l => `${l} = ${show(latest[l.toLowerCase() + "_mm"], 4)} mm`);
  setText("positions", "axis positions (scales): " + positions.join(", "));
  setText("last-fault", state.last_fault ? `last frame faulty: ${state.last_fault_text}` : "");
  const age = latest.t_s === null || latest.t_s === undefined || state.t_s === null ? null : state.t_s - latest.t_s;
  const stale = age !== null && age > STALE_S;
  $("point").classList.toggle("stale", stale);
  setText("stale", stale ? `no good frame for ${age.toFixed(1)} s: values are from t = ${show(latest.t_s, 3)} s` : "");
}

function drawSensors(state) {
  const body = $("sensors");
  if (body.childElementCount !== state.sensors.length) {
    body.textContent = "";
    for (const s of state.sensors) {
      const row = document.createElement("tr");
      row.id = "sensor-" + s.name;
      row.innerHTML = "<td></td><td></td><td></td><td></td><td></td><td></td>";
      row.cells[0].textContent = s.name;
      body.appendChild(row);
    }
  }
  const faulty = state.sensors.filter(s => s.state === "missing" || s.state === "out of range");
  const summary = $("sensor-summary");
  if (!state.sensors.some(s => s.state !== "waiting")) {
    setText("sensor-summary", "waiting for frames");
    summary.className = "summary waiting";
  } else if (faulty.length) {
    setText("sensor-summary", `${faulty.length} of ${state.sensors.length} faulty: ` + faulty.map(s => `${s.name} ${s.state}`).join(", "));
    summary.className = "summary bad";
  } else {
    setText("sensor-summary", `all ${state.sensors.length} ok`);
    summary.className = "summary ok";
  }
  state.sensors.forEach((s, i) => {
    const cells = body.rows[i].cells;
    cells[1].textContent = show(s.value, 4);
    cells[2].textContent = s.state;
    cells[2].className = "state-" + s.state.replace(/ /g, "-");
    body.rows[i].dataset.state = s.state;
    cells[3].textContent = `${limit(s.low)} \u2026 ${limit(s.high)}`;
    cells[4].textContent = String(s.missing);
    cells[5].textContent = String(s.out_of_range);
  });
}

function drawHeader(state) {
  setText("title", state.title || "axiscal live");
  setText("frames", String(state.frames));
  setText("rate", String(Math.round(state.rate_hz)));
  setText("faults", String(state.faults));
  if (state.source) {
    setText("source", state.source.description);
    const badge = $("source-state");
    badge.textContent = state.source.state + (state.source.retries ? ` (${state.source.retries} retries)` : "");
    badge.className = "badge " + state.source.state;
    setText("source-message", state.source.state === "streaming" ? "" : state.source.message || "");
  }
  setText("latency", state.latency_ms ? show(state.latency_ms.p99, 2) : "-");
  setText("recorded", state.record ? `${state.record.acknowledged} / ${state.record.written}` : "off");
}

function draw() {
  const state = pending;
  pending = null;
  if (!state) return;
  buildAxes(state);
  drawHeader(state);
  drawLatest(state);
  drawHistory(state);
  drawAxes(state);
  drawSensors(state);
  document.body.dataset.version = String(state.version);
}

function schedule(state) {
  const first = pending === null;
  pending = state;
  if (first) {
    if (document.hidden) setTimeout(draw, 0); else requestAnimationFrame(draw);
  }
}

function connect(delay) {
  const socket = new WebSocket(`ws://${location.host}/ws`);
  const badge = $("connection");
  socket.onopen = () => { badge.textContent = "live"; badge.className = "badge ok"; delay = 500; };
  socket.onmessage = event => schedule(JSON.parse(event.data));
  socket.onclose = () => {
    badge.textContent = "disconnected, retrying";
    badge.className = "badge retrying";
    setTimeout(() => connect(Math.min(delay * 2, 5000)), delay);
  };
}

connect(500);
