"""Questions: the grammar of questions about the situation, their answers from the snapshot, and
questions about what people told."""
