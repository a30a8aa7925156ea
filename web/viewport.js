// glint's page: the image's viewport: zoom, panning, and a dragged region to render.
"use strict";

// Nearest-neighbour magnification; the viewport scrolls, and dragging pans it (or, with the
// Region toggle on, selects a rectangle to render).
function setZoom(z) {
  zoom = z;
  for (const b of document.querySelectorAll("button.zoom")) b.classList.toggle("active", Number(b.dataset.zoom) === z);
  hideRegionBox();
  applyZoom();
}
function applyZoom() {
  if (ui.image.naturalWidth) ui.image.style.width = `${ui.image.naturalWidth * zoom}px`;
}

function toggleRegionMode() {
  const on = ui.regionMode.getAttribute("aria-pressed") !== "true";
  ui.regionMode.setAttribute("aria-pressed", String(on));
  ui.regionMode.classList.toggle("active", on);
  ui.viewport.classList.toggle("selecting", on);
}
const regionMode = () => ui.regionMode.getAttribute("aria-pressed") === "true";

// "Denoised" shows the shown job's latest frame denoised (image.denoised.png, made by the server
// on request) in place of the unbiased image; off, the unbiased stream or PNG comes back.
function toggleDenoised() {
  const on = !denoisedShown();
  ui.denoised.setAttribute("aria-pressed", String(on));
  if (on && samplesView) {  // one view in place of the image
    samplesView = false;
    ui.samplesView.setAttribute("aria-pressed", "false");
  }
  denoisedFrame = 0;
  if (shown) showImage(shown.status);
}
const denoisedShown = () => ui.denoised.getAttribute("aria-pressed") === "true";
let denoisedFrame = 0;  // the frame whose denoised image is shown or loading

// The shown job's image: live, the multipart stream; ended, its last PNG; with "Denoised" on,
// the denoised frame, asked for again when a newer frame exists and the last request has ended
// (making one takes the server a while: requests never pile up).
function showImage(status) {
  if (!denoisedShown()) {
    if (shown?.events) ui.image.src = withToken(status.urls.stream);
    else showFinalImage(status);
    return;
  }
  if (status.frame === 0 || status.frame === denoisedFrame || (denoisedFrame && !ui.image.complete)) return;
  denoisedFrame = status.frame;
  ui.image.src = withToken(`${status.urls.denoised}?frame=${status.frame}`);
}

// A denoised frame the server refused (429: it is making as many previews as it may) is asked
// for again a moment later.
function retryDenoised() {
  if (!denoisedShown() || !denoisedFrame) return;
  denoisedFrame = 0;
  setTimeout(() => { if (denoisedShown() && shown) showImage(shown.status); }, 2000);
}

// The image pixel under a pointer, in the shown image's pixels (fractional; may lie outside).
// The bounding box already holds the zoom, the scroll and the centring.
function imagePoint(e) {
  const r = ui.image.getBoundingClientRect();
  return { x: (e.clientX - r.left) * ui.image.naturalWidth / r.width,
           y: (e.clientY - r.top) * ui.image.naturalHeight / r.height };
}

// The pixels a drag from a to b covers, both ends included, clamped to the image: x1, y1 exclusive.
function pixelRect(a, b) {
  const clamp = (v, lo, hi) => Math.min(hi, Math.max(lo, v));
  const w = ui.image.naturalWidth, h = ui.image.naturalHeight;
  return {
    x0: clamp(Math.floor(Math.min(a.x, b.x)), 0, w - 1), y0: clamp(Math.floor(Math.min(a.y, b.y)), 0, h - 1),
    x1: clamp(Math.floor(Math.max(a.x, b.x)) + 1, 1, w), y1: clamp(Math.floor(Math.max(a.y, b.y)) + 1, 1, h),
  };
}

// The overlay sits on the image in #stage, snapped to whole image pixels at the current zoom.
function showRegionBox(rect) {
  const scale = ui.image.getBoundingClientRect().width / ui.image.naturalWidth;
  Object.assign(ui.regionBox.style, {
    left: `${rect.x0 * scale}px`, top: `${rect.y0 * scale}px`,
    width: `${(rect.x1 - rect.x0) * scale}px`, height: `${(rect.y1 - rect.y0) * scale}px`,
  });
  ui.regionBox.title = `${rect.x1 - rect.x0} × ${rect.y1 - rect.y0}`;
  ui.regionBox.hidden = false;
}
function hideRegionBox() { ui.regionBox.hidden = true; }

// A new job of the shown image's full size with the current controls, rendering only the
// selected window. The shown image may itself be a region job's window: its offset is added.
function renderRegion(rect) {
  const s = shown.status;
  const frame = s.region || { x0: 0, y0: 0, full_width: s.width, full_height: s.height };
  const region = [frame.x0 + rect.x0, frame.y0 + rect.y0, frame.x0 + rect.x1, frame.y0 + rect.y1];
  submit(requestBody({ width: frame.full_width, height: frame.full_height, region }));
}

function enableDragging() {
  let drag = null;
  ui.viewport.addEventListener("pointerdown", (e) => {
    const selecting = regionMode() && shown && ui.image.naturalWidth > 0;
    drag = { selecting, x: e.clientX, y: e.clientY, left: ui.viewport.scrollLeft, top: ui.viewport.scrollTop,
             from: selecting && imagePoint(e) };
    ui.viewport.classList.toggle("panning", !selecting);
    ui.viewport.setPointerCapture(e.pointerId);
  });
  ui.viewport.addEventListener("pointermove", (e) => {
    if (!drag) return;
    if (drag.selecting) return showRegionBox(pixelRect(drag.from, imagePoint(e)));
    ui.viewport.scrollLeft = drag.left - (e.clientX - drag.x);
    ui.viewport.scrollTop = drag.top - (e.clientY - drag.y);
  });
  ui.viewport.addEventListener("pointerup", (e) => {
    // A click is not a selection: a region needs a drag of a few screen pixels.
    const moved = drag && Math.hypot(e.clientX - drag.x, e.clientY - drag.y) >= 3;
    if (drag?.selecting && moved) renderRegion(pixelRect(drag.from, imagePoint(e)));
    else if (drag?.selecting) hideRegionBox();
    stopDrag();
  });
  const stopDrag = () => { drag = null; ui.viewport.classList.remove("panning"); };
  ui.viewport.addEventListener("pointercancel", () => { hideRegionBox(); stopDrag(); });
}
