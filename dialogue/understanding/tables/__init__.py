"""The tables of a language folder's files, as typed models (dialogue.understanding.language reads
them): one module per file (`words.toml`: `tables.words`), a table a file leaves out empty, any other
key refused. `base` holds what they are made of; `prefixes` how a stage looks up a table of phrases
at a text's start."""
