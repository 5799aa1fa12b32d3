"""Intents pushed to the middleware as they are emitted: the events, and the bus that numbers,
buffers and fans them out (the service streams them over SSE and WebSocket and POSTs them to
webhooks: api.routes.intents, api.webhooks)."""
