"""i18n_msgs on the chatbot: ``~/get_supported_locales`` (GetLocales) and ``~/set_default_locale``
(SetLocale, an action with ``progress`` feedback).

The supported locales are those REST's ``GET /locales`` answers: the offline rules' English, or any
(an empty list) with a model that reads prompts. The default locale is the node's ``default_locale``
parameter (a ROS parameter, so ``ros2 param set`` changes it too, checked the same way): the locale
of the dialogues started over ROS without one, and of the voices' turns. A locale that is no
language tag, or that the service cannot answer in, is refused with ``error_msg`` (the goal aborted);
nothing changes.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import Any

from i18n_msgs.action import SetLocale
from i18n_msgs.srv import GetLocales
from rclpy.action import ActionServer
from rclpy.parameter import Parameter

from api.ros.node.front import Front
from api.ros.parameters import ParameterError, locale_value
from dialogue.locales import is_english, supported_locales

#: What the feedback's progress reports (i18n_msgs' convention: a JSON object per component).
DONE = json.dumps({"chatbot": "complete"})


class Locales:
    def __init__(self, front: Front) -> None:
        self.front = front
        self.model = front.services.model

    def supported(self) -> list[str]:
        return supported_locales(reads_prompts=self.model.llm is not None)

    def get(self, request: Any, response: Any) -> Any:
        response.locales = self.supported()
        return response

    def refusal(self, locale: str) -> str | None:
        """Why the service cannot take ``locale`` as its default; None: it can."""
        try:
            value = locale_value(locale)
        except ParameterError as exc:
            return str(exc)
        if value and self.supported() and not is_english(value):
            return (f"the offline rules understand English only ({', '.join(self.supported())}); a model "
                    f"backend (--llm hybrid:...) answers in {value}")
        return None

    def set_default(self, handle: Any) -> Any:
        """The SetLocale goal: checked, then the parameter set (which the node checks again)."""
        locale = handle.request.locale
        why = self.refusal(locale)
        if why is None:
            outcome = self.front.chatbot_node.set_parameters(
                [Parameter("default_locale", Parameter.Type.STRING, locale_value(locale))])[0]
            why = None if outcome.successful else outcome.reason
        if why is not None:
            handle.abort()
            return SetLocale.Result(error_msg=why)
        handle.publish_feedback(SetLocale.Feedback(progress=DONE))
        handle.succeed()
        return SetLocale.Result(error_msg="")


def attach(front: Front) -> Callable[[], None]:
    locales = Locales(front)
    node = front.chatbot_node
    service = node.create_service(GetLocales, "~/get_supported_locales", locales.get)
    action = ActionServer(node, SetLocale, "~/set_default_locale", execute_callback=locales.set_default)

    def detach() -> None:
        action.destroy()
        node.destroy_service(service)

    return detach
