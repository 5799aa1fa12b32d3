// The service's HTTP routes, as used by the viewer. The token (if any) lives in sessionStorage so
// it is forgotten with the tab.

const TOKEN_KEY = "situated.token";

export class ApiError extends Error {
  constructor(status, code, message) {
    super(message);
    this.status = status;
    this.code = code;
  }
}

// A failure that may pass: the service unreachable (0), too busy (429) or failing (5xx).
export function passing(err) {
  return err instanceof ApiError && (err.status === 0 || err.status === 429 || err.status >= 500);
}

export function getToken() {
  return sessionStorage.getItem(TOKEN_KEY) || "";
}

export function setToken(token) {
  if (token) sessionStorage.setItem(TOKEN_KEY, token);
  else sessionStorage.removeItem(TOKEN_KEY);
}

async function call(method, path, body, onHeaders) {
  const headers = { Accept: "application/json" };
  const token = getToken();
  if (token) headers.Authorization = `Bearer ${token}`;
  if (body !== undefined) headers["Content-Type"] = "application/json";
  let response;
  try {
    response = await fetch(path, { method, headers, body: body === undefined ? undefined : JSON.stringify(body) });
  } catch (err) {
    throw new ApiError(0, "network", `the service did not answer (${err.message})`);
  }
  if (onHeaders) onHeaders(response.headers);
  const text = await response.text();
  let data = null;
  try { data = text ? JSON.parse(text) : null; } catch { data = text; }
  if (!response.ok) {
    // Every route answers errors as {status, code, message, details}.
    const message = data && typeof data === "object" && data.message ? data.message : `HTTP ${response.status}`;
    throw new ApiError(response.status, data && data.code ? data.code : "error", message);
  }
  return data;
}

const enc = encodeURIComponent;

export const api = {
  // origin=true asks for an "asserted" flag per relation; a service without it ignores the flag.
  details: (term) => call("GET", `/kb/details/${enc(term)}?origin=true`),
  classesof: (term) => call("GET", `/kb/classesof/${enc(term)}`),
  query: (patterns) => call("POST", "/kb/query", { patterns }),
  revise: (statements, method) => call("POST", "/kb/revise", { statements, method }),
  // The answer, with `turn`: the id of the turn's trace (the X-Situated-Turn header).
  async interact(userId, input) {
    let turn = null;
    const answer = await call("POST", "/dialogues/default/interactions", { user_id: userId, input },
      (headers) => { turn = headers.get("X-Situated-Turn"); });
    return { ...answer, turn };
  },
  turns: (dialogueId) => call("GET", `/dialogues/${enc(dialogueId)}/turns`),
  // The commit feed: what each write added and removed, so removals show without polling.
  changesUrl() {
    const token = getToken();
    return token ? `/kb/changes?access_token=${enc(token)}` : "/kb/changes";
  },
};
