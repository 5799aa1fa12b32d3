"""Model backends behind one protocol (`dialogue.llm.base.ChatModel`), one small module each."""
