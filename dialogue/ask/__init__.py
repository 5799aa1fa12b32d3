"""The ask role (chatbot_msgs `__ask__`, `/skill/ask`): ask a question, read each answer into the
fields of a JSON schema, ask again only for what is missing or invalid, and end with the results.

`form` (the configuration and the form's state), `fields` (one finder per kind of field; the offline
reading of an answer is dialogue.understanding.followups.form), `progress` (the form after an answer
and the next line), `model` (the per-turn schema and prompt for a model, and the validation of its
answer), `turn` (one turn of the role on the dialogue engine).
"""

from dialogue.ask.form import ASK_ROLE, AskError, AskForm, FormState, parse_configuration

__all__ = ["ASK_ROLE", "AskError", "AskForm", "FormState", "parse_configuration"]
