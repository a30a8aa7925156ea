// glint's page: the estimated-error plot beside the figures.
"use strict";

// Estimated error against time on log-log axes: a straight line of slope -1/2 when all is well.
// The job's target error, if it has one, is a dashed line inside the y range, so the distance
// left to it is seen at once.
function drawPlot(target) {
  const ctx = ui.plot.getContext("2d");
  const { width: w, height: h } = ui.plot;
  ctx.clearRect(0, 0, w, h);
  ctx.fillStyle = "#9a9ca3";
  ctx.font = "10px sans-serif";
  ctx.fillText("est. error vs time (log-log)", 6, 12);
  if (errorHistory.length === 0) {
    if (target) drawTarget(ctx, h / 2, w, target);  // no error yet: the line alone, mid-height
    return;
  }
  const xs = errorHistory.map(([t]) => Math.log10(t)), ys = errorHistory.map(([, e]) => Math.log10(e));
  const yAll = target ? [...ys, Math.log10(target)] : ys;
  const [x0, x1] = [Math.min(...xs), Math.max(...xs)], [y0, y1] = [Math.min(...yAll), Math.max(...yAll)];
  const px = (x) => 8 + (w - 16) * (x - x0) / (x1 - x0 || 1);
  const py = (y) => h - 8 - (h - 28) * (y - y0) / (y1 - y0 || 1);
  if (target) drawTarget(ctx, py(Math.log10(target)), w, target);
  ctx.strokeStyle = "#4f8cf0";
  ctx.lineWidth = 1.5;
  ctx.setLineDash([]);
  ctx.beginPath();
  xs.forEach((x, i) => (i ? ctx.lineTo(px(x), py(ys[i])) : ctx.moveTo(px(x), py(ys[i]))));
  ctx.stroke();
  ctx.fillStyle = "#9a9ca3";
  ctx.fillText(`${format(errorHistory[errorHistory.length - 1][1])}`, w - 50, 12);
}

function drawTarget(ctx, y, w, target) {
  ctx.strokeStyle = ctx.fillStyle = "#e8a33d";
  ctx.lineWidth = 1;
  ctx.setLineDash([5, 4]);
  ctx.beginPath();
  ctx.moveTo(8, Math.round(y) + 0.5);
  ctx.lineTo(w - 8, Math.round(y) + 0.5);
  ctx.stroke();
  ctx.fillText(`target ${format(target, 2)}`, 10, y < 24 ? y + 12 : y - 3);
}
