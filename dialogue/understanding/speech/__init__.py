"""What was heard or typed, read as the grammar's words: plain words (contractions, fillers,
politeness), names spelled out, typos, misheard names and homophones, self-repairs and vocatives,
and run-on speech cut into clauses."""
