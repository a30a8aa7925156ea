// glint's page: talking to the server. Every request goes through api(), which adds the
// bearer token when the server needs one.
"use strict";

// The server's bearer token, when it needs one (glint serve --token): from the URL fragment
// (#token=...), kept for this tab's session, or asked for when the server answers 401. fetch
// sends it as a header; <img>, download links and EventSource cannot, so their URLs carry it
// as ?token= (the server accepts that on the stream, events and image routes only).
const auth = { token: new URLSearchParams(location.hash.slice(1)).get("token") || sessionStorage.getItem("glint-token") || "" };
if (location.hash.includes("token=")) window.history.replaceState(null, "", location.pathname + location.search);
if (auth.token) sessionStorage.setItem("glint-token", auth.token);

function withToken(url) {
  return auth.token ? `${url}${url.includes("?") ? "&" : "?"}token=${encodeURIComponent(auth.token)}` : url;
}

// `ask` false: a 401 is returned as it is. The jobs panel polls in the background and must not
// pop up a prompt every second; a user action (Render, a row's buttons) asks.
async function api(url, options = {}, ask = true) {
  const send = () => fetch(url, {
    ...options, headers: { ...options.headers, ...(auth.token && { Authorization: `Bearer ${auth.token}` }) },
  });
  const response = await send();
  if (response.status !== 401 || !ask) return response;
  const token = window.prompt("This glint server needs its access token:");
  if (!token) return response;
  auth.token = token;
  sessionStorage.setItem("glint-token", token);
  return send();
}

const sendJson = (url, method, body) =>
  api(url, { method, headers: { "Content-Type": "application/json" }, body });
