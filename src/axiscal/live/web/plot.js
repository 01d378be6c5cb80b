// Line charts on a canvas: axes with round-number ticks, one or more series, gaps where a value is null.
"use strict";

function niceStep(span, count) {
  const raw = span / Math.max(count, 1);
  const power = Math.pow(10, Math.floor(Math.log10(raw)));
  const unit = raw / power;
  return (unit < 1.5 ? 1 : unit < 3.5 ? 2 : unit < 7.5 ? 5 : 10) * power;
}

function extent(arrays) {
  let lo = Infinity, hi = -Infinity;
  for (const values of arrays) {
    for (const v of values) {
      if (v === null || !isFinite(v)) continue;
      if (v < lo) lo = v;
      if (v > hi) hi = v;
    }
  }
  if (lo === Infinity) return null;
  if (hi - lo < 1e-9) { lo -= 0.5; hi += 0.5; }
  return [lo, hi];
}

function formatTick(v, step) {
  const digits = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  return v.toFixed(Math.min(digits, 6));
}

// series: [{values: [...], color: "#...", label: "..."}]; options: {xlabel, ylabel, title, xrange: [lo, hi] (default: the data's)}
function drawChart(canvas, xs, series, options) {
  const width = canvas.width, height = canvas.height;
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, width, height);
  ctx.font = "12px system-ui, sans-serif";
  const left = 58, right = 10, top = options.title ? 20 : 8, bottom = 30;
  const plotW = width - left - right, plotH = height - top - bottom;
  if (options.title) {
    ctx.fillStyle = "#1d2430";
    ctx.textAlign = "left";
    ctx.fillText(options.title, left, 13);
  }
  const xr = options.xrange || extent([xs]);
  const yr = extent(series.map(s => s.values));
  ctx.strokeStyle = "#d9dee6";
  ctx.strokeRect(left, top, plotW, plotH);
  if (!xr || !yr) {
    ctx.fillStyle = "#6b7686";
    ctx.textAlign = "center";
    ctx.fillText("waiting for data", left + plotW / 2, top + plotH / 2);
    return false;
  }
  const pad = (yr[1] - yr[0]) * 0.08;
  const y0 = yr[0] - pad, y1 = yr[1] + pad;
  const px = x => left + (x - xr[0]) / (xr[1] - xr[0] || 1) * plotW;
  const py = y => top + (1 - (y - y0) / (y1 - y0)) * plotH;
  ctx.fillStyle = "#6b7686";
  ctx.lineWidth = 1;
  const ys = niceStep(y1 - y0, 4);
  ctx.textAlign = "right";
  for (let v = Math.ceil(y0 / ys) * ys; v <= y1; v += ys) {
    ctx.strokeStyle = "#eef1f5";
    ctx.beginPath(); ctx.moveTo(left, py(v)); ctx.lineTo(left + plotW, py(v)); ctx.stroke();
    ctx.fillText(formatTick(v, ys), left - 5, py(v) + 4);
  }
  const xsStep = niceStep(xr[1] - xr[0], 6);
  ctx.textAlign = "center";
  for (let v = Math.ceil(xr[0] / xsStep) * xsStep; v <= xr[1]; v += xsStep) {
    ctx.fillText(formatTick(v, xsStep), px(v), top + plotH + 14);
  }
  if (options.xlabel) ctx.fillText(options.xlabel, left + plotW / 2, height - 3);
  if (options.ylabel) {
    ctx.save(); ctx.translate(12, top + plotH / 2); ctx.rotate(-Math.PI / 2);
    ctx.fillText(options.ylabel, 0, 0); ctx.restore();
  }
  ctx.lineWidth = 1.6;
  const present = (values, i) => i >= 0 && i < xs.length && xs[i] !== null && values[i] !== null && isFinite(xs[i]) && isFinite(values[i]);
  for (const s of series) {
    ctx.strokeStyle = s.color;
    ctx.fillStyle = s.color;
    ctx.beginPath();
    for (let i = 0; i < xs.length; i++) {
      if (!present(s.values, i)) continue;
      if (present(s.values, i - 1)) ctx.lineTo(px(xs[i]), py(s.values[i])); else ctx.moveTo(px(xs[i]), py(s.values[i]));
    }
    ctx.stroke();
    for (let i = 0; i < xs.length; i++) {
      if (present(s.values, i) && !present(s.values, i - 1) && !present(s.values, i + 1)) {
        ctx.fillRect(px(xs[i]) - 2.5, py(s.values[i]) - 2.5, 5, 5);
      }
    }
  }
  return true;
}
