"""The service's health (``/health``'s detailed report) as ROS diagnostics statuses (REP 107), one per
concern: the service as a whole, the KB, the dialogue model, each component (journal, store mirror,
webhooks...). The ROS node publishes them on ``/diagnostics``; this module needs no ROS.

Levels: the service is OK, or WARN while degraded (it still answers: a model that is down gets the
polite fallback), with the reasons as its message; the KB and the model are OK or ERROR (not
reachable); a component is OK or WARN.

>>> report = {"status": "ok", "reasons": [], "kb": {"revision": 3}, "components": {},
...           "model": {"name": "rules", "reachable": True, "detail": "in-process"}}
>>> [(s.level, s.name, s.message) for s in statuses(report)]  # doctest: +NORMALIZE_WHITESPACE
[(0, 'situated: service', 'ok'), (0, 'situated: KB', 'revision 3'),
 (0, 'situated: model', 'rules: in-process')]
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

#: diagnostic_msgs/DiagnosticStatus levels.
OK, WARN, ERROR = 0, 1, 2
HARDWARE_ID = "situated"


@dataclass(frozen=True)
class Status:
    level: int
    name: str
    message: str
    values: tuple[tuple[str, str], ...] = ()


def _values(mapping: Mapping[str, Any], skip: frozenset[str] = frozenset()) -> tuple[tuple[str, str], ...]:
    return tuple((key, ", ".join(map(str, value)) if isinstance(value, list) else str(value))
                 for key, value in mapping.items() if key not in skip)


def statuses(report: Mapping[str, Any], extra: Mapping[str, Any] | None = None) -> list[Status]:
    """``report`` (``healthreport.health_report(..., details=True)``) as statuses; ``extra``: more
    values of the service's (the node's own counts)."""
    degraded = report["status"] != "ok"
    counts = {f"{part} {key}": value for part in ("events", "intents")
              for key, value in (report.get(part) or {}).items()}
    service = Status(WARN if degraded else OK, "situated: service", "; ".join(report["reasons"]) or "ok",
                     (("Module name", HARDWARE_ID), ("status", report["status"]), *_values(counts),
                      *_values(extra or {})))
    kb = report["kb"]
    reachable = kb.get("reachable", True)
    kb_status = Status(OK if reachable else ERROR, "situated: KB",
                       f"revision {kb['revision']}" if reachable else f"not reachable: {kb.get('error', '')}",
                       _values(kb))
    model = report["model"]
    model_status = Status(OK if model["reachable"] else ERROR, "situated: model",
                          f"{model['name']}: {model['detail']}" if model["reachable"]
                          else f"{model['name']} is not reachable ({model['detail']})", _values(model))
    components = [Status(OK if state.get("ok") else WARN, f"situated: {name}",
                         "ok" if state.get("ok") else str(state.get("reason", "not ok")),
                         _values(state, frozenset({"ok"})))
                  for name, state in report.get("components", {}).items()]
    return [service, kb_status, model_status, *components]
