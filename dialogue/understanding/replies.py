"""The rules' spoken acknowledgements: how a taken-on intent is said back to the person."""

from __future__ import annotations

from dialogue import intents as I
from dialogue.reference.grounding import Snapshot
from dialogue.understanding.outcome import Ref
from dialogue.understanding.questions import answers


def vocative(snapshot: Snapshot, speaker: str) -> str:
    """A leading space and the name (" Alice") to address a speaker the KB knows by name, else nothing."""
    me = snapshot.get(speaker)
    return f" {me.name}" if me is not None and me.labels else ""


def _name(snapshot: Snapshot, speaker: str, ref: Ref | None) -> str:
    if ref is None:
        return "it"
    if ref.speaker:
        return "you"
    return answers.the(snapshot, ref.entity, speaker) if ref.entity else "it"


#: How a place said with a preposition is said back ("next to the laptop", not "on the laptop").
_SAID_BACK = {"beside": "next to", "near": "near", "under": "under", "underneath": "under",
              "beneath": "under", "below": "under", "in": "in", "into": "in", "inside": "in", "at": "at",
              "by": "by", "behind": "behind", "against": "against", "in front of": "in front of"}  # fmt: skip
#: "wave at Ana", "shake hands with Ana"; other motions are done for someone.
_TOWARDS = {"wave": "at", "point": "at", "nod": "at", "smile": "at", "shake hands": "with"}


def acknowledgement(snapshot: Snapshot, speaker: str, intent: str, roles: dict[str, str],
                    refs: dict[str, Ref], said: str | None = None) -> str:
    """What the robot says when it takes on an intent ("OK, I will bring the cup to you."); `said`
    is the preposition the person put the place with, if any."""
    obj, rec, goal = (_name(snapshot, speaker, refs.get(r)) for r in ("object", "recipient", "goal"))
    text = roles.get("object", "").replace("_", " ")
    match intent:
        case I.GRAB_OBJECT:
            return f"OK, I will pick up {obj}."
        case I.BRING_OBJECT:
            return f"OK, I will bring {obj} to {rec}."
        case I.PLACE_OBJECT:
            ref = refs.get("recipient")
            zone = ref is not None and ref.entity is not None and ref.entity.kind == "zone"
            prep = _SAID_BACK.get(said or "", "in" if zone else "on")
            return f"OK, I will put {obj if 'object' in refs else 'it'} {prep} {rec}."
        case I.MOVE_TO:
            return "OK, I am coming." if goal == "you" else f"OK, I am going to {goal}."
        case I.GUIDE:
            who = "take you" if rec == "you" else f"guide {rec}"
            return f"OK, I will {who} to {goal}."
        case I.GREET:
            return f"OK, I will greet {rec}."
        case I.SAY:
            return f"OK, I will tell {rec}: {text}." if "recipient" in refs else f"OK: {text}."
        case I.ENGAGE_WITH:
            return f"OK, I will go and talk to {rec}."
        case I.PERFORM_MOTION:
            prep = _TOWARDS.get(text, "for")
            return f"OK, I will {text} {prep} {rec}." if "recipient" in refs else f"OK, I will {text}."
        case I.START_ACTIVITY:
            return f"OK, I am starting: {text}."
        case I.STOP_ACTIVITY:
            return f"OK, I will stop {text}." if text else "OK, I am stopping."
        case I.WAKEUP:
            return "I am awake!"
        case I.SUSPEND:
            return "OK, I will go to sleep."
    return "OK."
