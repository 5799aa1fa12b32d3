"""The offline rules grammar: utterances to intents without a model."""
