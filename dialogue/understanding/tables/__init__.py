"""The tables of a language folder's files, as typed models (dialogue.understanding.language reads
them): one module per file (`words.toml`: `tables.words`), a table a file leaves out empty, any other
key refused. `base` holds what they are made of."""
