"""The grammar's word lists, in one place: how people pad, repair and soften what they ask, and the
prepositions, particles and adjuncts of requests.

Data only. Verbs are in the frame table (dialogue.understanding.requests.frames), closed-class
English shared with reference resolution in dialogue.reference.english, and nouns always come from
the KB.
"""

from __future__ import annotations

from dialogue.reference.english import Words, phrases, word_set

_SPOKEN: dict[str, Words] = {
    "what's": ("what", "is"), "where's": ("where", "is"), "who's": ("who", "is"), "that's": ("that", "is"),
    "it's": ("it", "is"), "there's": ("there", "is"), "let's": ("let", "us"), "i'd": ("i", "would"),
    "can't": ("cannot",), "i'm": ("i", "am"), "you're": ("you", "are"), "here's": ("here", "is"),
    "dont": ("don't",), "doesn't": ("don't",), "won't": ("don't",),
    # Speech recognisers and chat drop the apostrophe.
    "whats": ("what", "is"), "wheres": ("where", "is"), "whos": ("who", "is"), "thats": ("that", "is"),
    "theres": ("there", "is"), "heres": ("here", "is"), "shes": ("she", "is"), "hes": ("he", "is"),
    "im": ("i", "am"), "ive": ("i", "have"), "youre": ("you", "are"), "cant": ("cannot",),
    "doesnt": ("don't",), "wont": ("don't",), "isnt": ("is", "not"), "arent": ("are", "not"),
    "didnt": ("did", "not"), "i've": ("i", "have"), "she's": ("she", "is"), "he's": ("he", "is"),
    "we're": ("we", "are"), "they're": ("they", "are"), "hows": ("how", "is"),
    "theyre": ("they", "are"), "theyve": ("they", "have"), "youve": ("you", "have"), "weve": ("we", "have"),
    "youll": ("you", "will"), "theyll": ("they", "will"), "itll": ("it", "will"), "thatll": ("that", "will"),
    "wasnt": ("was", "not"), "werent": ("were", "not"), "hasnt": ("has", "not"), "havent": ("have", "not"),
    "couldnt": ("could", "not"), "wouldnt": ("would", "not"), "shouldnt": ("should", "not"),
    "youd": ("you", "would"), "theyd": ("they", "would"), "whatre": ("what", "are"),
    "whered": ("where", "did"), "it'll": ("it", "will"), "you'll": ("you", "will"),
    "that'd": ("that", "would"), "thatd": ("that", "would"), "it'd": ("it", "would"), "itd": ("it", "would"),
    "you'd": ("you", "would"), "we'd": ("we", "would"), "they'd": ("they", "would"),
    "they've": ("they", "have"), "you've": ("you", "have"),
    "gimme": ("give", "me"), "lemme": ("let", "me"), "wanna": ("want", "to"), "gotta": ("have", "to"),
    "gonna": ("going", "to"),
}  # fmt: skip
#: Chat abbreviations, read as the words they stand for ("can u get my bag n bring it over", "go bk
#: to the desk", "whats on the counter rn"). Words spelled out letter by letter ("s u v") are
#: joined before these are read (dialogue.understanding.speech.letters).
#: After a determiner, an abbreviation is read as written: a noun ("where is the atm").
CHAT: dict[str, Words] = {
    "u": ("you",), "ya": ("you",), "r": ("are",), "ur": ("your",), "n": ("and",), "b4": ("before",),
    "bk": ("back",), "rn": ("right", "now"), "pls": ("please",), "plz": ("please",), "thx": ("thanks",),
    "ty": ("thank", "you"), "cos": ("because",), "cuz": ("because",), "coz": ("because",),
    "abt": ("about",), "tho": ("though",), "ppl": ("people",), "sth": ("something",),
    "smth": ("something",), "l8r": ("later",), "2moro": ("tomorrow",), "tmrw": ("tomorrow",),
    "bc": ("because",), "w8": ("wait",), "wat": ("what",), "wot": ("what",), "whr": ("where",),
    "cld": ("could",), "cud": ("could",), "wud": ("would",), "wld": ("would",), "shud": ("should",),
    "hv": ("have",), "em": ("them",), "yr": ("your",), "thnx": ("thanks",), "thanx": ("thanks",),
    "rly": ("really",), "dunno": ("don't", "know"), "2day": ("today",),
    "atm": ("at", "the", "moment"), "nvm": ("never", "mind"), "idk": ("i", "don't", "know"),
    "omw": ("on", "my", "way"), "prolly": ("probably",), "probs": ("probably",), "def": ("definitely",),
    "defo": ("definitely",), "kinda": ("kind", "of"), "sorta": ("sort", "of"), "outta": ("out", "of"),
    "cya": ("see", "you"), "msg": ("message",), "tomoz": ("tomorrow",), "2nite": ("tonight",),
    "tonite": ("tonight",), "yw": ("you", "are", "welcome"), "np": ("no", "problem"), "plzz": ("please",),
    "pleez": ("please",), "fone": ("phone",), "tnx": ("thanks",), "rite": ("right",), "nite": ("night",),
    "cus": ("because",), "ovr": ("over",), "cn": ("can",), "wat's": ("what", "is"), "wot's": ("what", "is"),
    "wats": ("what", "is"), "gd": ("good",), "frm": ("from",), "wiv": ("with",),
}  # fmt: skip
#: Every written form read as other words: contractions, with or without the apostrophe, and chat.
CONTRACTIONS: dict[str, Words] = {**_SPOKEN, **CHAT}
#: Hesitations and discourse fillers, dropped wherever they occur ("put the uh candle on the table").
FILLERS = word_set("um umm uh uhh er erm hmm mm ah really lol btw tbh")
#: Two-word fillers dropped wherever they occur.
FILLER_PAIRS = frozenset({("you", "know"), ("i", "guess"), ("of", "course")})
#: Words around "you know" that make it a question, not a filler ("do you know where...").
ASKING = word_set("do did don't if would as you that whether about him her them it")
#: Whose a thing is, said alone ("it's mine", "mine, obviously"): the possessive of its phrase ("my cup").
OWNERS = {"mine": "my", "yours": "your", "ours": "our", "hers": "her", "his": "his", "theirs": "their"}
#: Words of an answer that only add emphasis ("mine, obviously", "the red one definitely").
INTERJECTIONS = word_set(
    "obviously definitely clearly surely certainly naturally yes yeah yep sure please thanks"
)
#: A self-repair: what follows replaces the request said before it ("bring me the uh no wait put...").
REPAIRS = phrases(
    "no wait|wait no|sorry i mean|no sorry|i mean|or rather|no no|scratch that|no actually|actually|"
    "oh wait|wait|sorry"
)
POLITE_PREFIXES = phrases(
    "would you mind|do you mind|i would like you to|i want you to|i need you to|i wish you would|"
    "go ahead and|go and|come and|could you|can you|would you|will you|please|kindly|just|now|ok|okay|"
    "so|and|then|also|well|robot|let us|try to|you should|you can|you could|be so kind and|be so kind as to|"
    "time to|maybe|hold on|hang on|wait a moment|wait a second|one moment|actually|oh|um|umm|uh|er|erm|"
    "great|alright|all right|right|right then|cool|perfect|excellent|sorry|excuse me|can we|could we|"
    "shall we|should we|you must|you have to|you need to|you will|"
    "why don't we|how about we|i was wondering if you could|i wonder if you could|"
    "i was wondering whether you could|"
    "be a dear and|be an angel and|do me a favour and|do me a favor and|you know what|off you|listen|"
    "would you be so kind as to|would you be able to|are you able to|if you could|if you can"
)
#: Politeness at the end of a request that is said to the robot, never part of a message to pass on.
ROBOT_SUFFIXES = phrases(
    "please|thanks|thank you|if you can|if you could|ok|okay|would you|will you|could you|can you|won't you"
)
#: Words naming the listener after what was said to them ("you're in the way mate").
TAGS = "mate|pal|buddy|love|dear|darling|sir|madam|miss|boss|chief|my friend|my dear"
POLITE_SUFFIXES = (
    *ROBOT_SUFFIXES,
    *phrases("ta|cheers|thanks a lot|thank you very much|much appreciated|if you would|if you don't mind"),
    *phrases("now|right now|at the moment|for a moment|again|quickly|quick|immediately|for a sec|"
             "for a second|sorry|then"),
    # the listener named by a tag ("the yellow one mate", "over here love")
    *phrases(TAGS),
)
GREETINGS = tuple(sorted(phrases(  # longest first: "hello there" before "hello"
    "good morning|good afternoon|good evening|good day|hello|hi|hey|hiya|howdy|greetings|yo|"
    "hello there|hi there|hey there|welcome|morning|evening|afternoon"
), key=len, reverse=True))
#: Greetings that only call for attention before what follows ("hey robot, who's at the gate"):
#: greeting back is for the others ("hello robot, what's your name").
ATTENTION = frozenset(phrases("hey|hey there|yo|oi"))
SOCIAL = frozenset(
    phrases(
        "nice to see you|nice to meet you|good to see you|glad to see you|how are you|how are you doing|"
        "how is it going|there|robot|everyone|again|friend||how do you do"
    )
)
WH = word_set("what where who which how why when whose whom")
#: Words that never address someone by name at the start of an utterance.
NOT_VOCATIVE = word_set(
    "i you we he she it they there this that these those do does did is are was can could would will "
    "shall should may might must please let what where who which how why when whose the a an my your "
    "his her our their no not yes if and or but so then me us him them"
)
#: Filler words at the start of an utterance ("listen, go to the kitchen").
LEAD_FILLERS = word_set("listen look hey see")
#: Words that are never read as a verb's inflection ("does you..." is not "do").
AUXILIARIES = word_set("does did done is are was were be been being has had having am")

# -- requests -------------------------------------------------------------------------------------
#: Two-word prepositions read as one word, so that their "to" is never taken for a recipient's.
JOINED_PREPOSITIONS: dict[Words, str] = {("next", "to"): "beside", ("close", "to"): "near",
                                          ("nearest", "to"): "near", ("out", "of"): "from"}  # fmt: skip
#: Prepositions that introduce a place to put something ("put the cup on top of the piano").
PLACES = (
    "on top of|onto|on to|on|into|inside|in front of|in|at|to|under|underneath|beneath|below|beside|near|by|"
    "behind|against"
)
#: Prepositions that introduce where to go ("go over to the desk", "stand by the door").
GOALS = "to|towards|into|inside|onto|on|in|near|beside|over to|by"
#: Where to go, also said with a particle of motion before a noun phrase ("go down the compost area",
#: "pop round the shop"; "go down to the cellar" keeps "down" a particle, and "go down the hall to
#: the garage" makes "down the hall" the way).
GOAL_PARTICLES = word_set("down up round")
MOTION_GOALS = "|".join((GOALS, *sorted(GOAL_PARTICLES)))
#: Words between a verb of motion and its goal: "go back to", "head over to", "nip down to".
MOTION_PARTICLES = (
    "back over there straight right down up ahead across along out around round on and stand wait close "
    "closer quickly slowly carefully quietly safely directly through outside inside outdoors indoors "
    "upstairs downstairs"
)
#: Words between a verb of carrying and its object or recipient ("bring it over to me").
CARRY_PARTICLES = "over back up down along round around through out"
#: A place said by pointing at it: "come here", "leave it over there", "lead the way".
HERE = phrases("here|over here|back here|right here|closer")
THERE = phrases("there|over there|back there|the way")
#: Phrases that say how or when, not what or where ("on my behalf", "when you can"): never part of
#: a referent. A phrase that starts with a preposition the verb's frame uses is not one of them
#: ("bring the cup for me": "for me" is the recipient).
ADJUNCTS = phrases(
    "on my behalf|on our behalf|on his behalf|on her behalf|for me|for us|from me|from us|"
    "when you can|when you get a chance|when you have a moment|when you have a minute|when you are free|"
    "as soon as possible|as soon as you can|right away|straight away|at once|in a minute|in a moment|"
    "right now|at the moment|real quick|right quick|asap|in a jiffy|in a sec|in a second|instead|"
    "instead of that|"
    "a bit|a little|a little bit"
)
#: Where not to be ("move out of the way and go to the door"): said before where to go, or alone (a
#: move to no place the rules can name).
AWAY = phrases("out of the way|out the way|out of my way|out of your way|out of our way")
#: How long, never whom or where, whatever the verb ("bring the fan for now": no one is "now").
DURATIONS = phrases("for now|for the moment|for the time being|for a bit|for a while|for a minute|"
                    "for a few minutes|for the night|for the day")
ADJUNCTS = (*ADJUNCTS, *DURATIONS, *AWAY)
#: Conjunctions that start a clause of time to the end of a request ("hand Ana the menu *while she
#: waits*", "put the milk back *before it goes off*"): "while" always, the others before a subject
#: other than the robot ("after you wash it" asks for more than the request).
WHILE = word_set("while whilst")
TIME_CONJUNCTIONS = word_set("until till once before after as when")
THEIR_SUBJECTS = word_set("i he she we they it someone somebody anyone anybody everyone everybody people")
#: The starts of a condition that is only politeness, never a condition on the request ("if you
#: could...", "if possible", "if it's not too much trouble"); after any other subject a modal makes
#: it a request of its own ("if I could have the bill").
POLITE_IF = phrases(
    "if you|if possible|if so|if not|if it is not|if it's not|if its not|if it isn't|if it is no|"
    "if it's no|if that is ok|if that's ok|if thats ok|if that is alright|if that's alright|if ok"
)
IF_MODALS = word_set("could can may might would")
#: Words that stop what the robot is about before a negated request ("stop, don't go").
HALTS = word_set("stop wait hold")
#: Prepositions of a path: "go to the bathroom through the main door" (what follows is the adjunct).
PATHS = word_set("through via past across along")
#: Adverbs of manner, never part of a referent ("put the vase on the shelf carefully").
MANNER = word_set("carefully gently slowly quickly quietly safely")
#: A noun phrase of its own starts with one of these ("bring to Ana *the* tray").
NP_START = word_set("the a an this that these those my your his our their some")

#: Words a speech recogniser writes for one another (a number in a name most of all: "bay for").
HOMOPHONES = phrases(
    "for four fore|to two too|won one|ate eight|right write|through threw|sea see|pair pear|tee tea|"
    "there their|"
    "flour flower|whole hole|knight night|wood would|bare bear|mail male|meat meet|weight wait|"
    "piece peace|plain plane|deer dear|sale sail|steal steel|stair stare|board bored|sole soul"
)

#: Words of English a recogniser or a typist writes for a preposition, read as it before a noun
#: phrase of their own ("walk too the gate", "the milk form the jug"): no noun phrase starts
#: right after them otherwise.
PREPOSITION_SLIPS = {
    "too": "to", "two": "to", "2": "to", "form": "from", "fro": "from", "thru": "through", "four": "for",
    "4": "for", "fore": "for",
}  # fmt: skip

# -- small constructions --------------------------------------------------------------------------
#: "I want X" and friends ask for X to be brought.
WANTS = phrases(
    "i want|i need|i would like|can i have|could i have|may i have|can i get|could i get|i will have|"
    "give me|i could use|i could do with|i would love|i would really like|i fancy|we want|we need|"
    "we would like|can we have|could we have|may we have|can we get|could we get|we will have"
)
WANT_VERBS = word_set("want wants need needs")
#: "Ahmed would like the album", "he needs his glasses": someone else's wish, brought to them.
THEIR_WANTS = phrases("would like|would love|wants|needs|could use|could do with|fancies|is after")
#: Pronouns that may wish for something in those words; a name may too, but not a phrase with an
#: article ("the kettle needs descaling") or the speaker or robot ("I", "you": other constructions).
WISHERS = word_set("he she they")
NOT_WISHERS = word_set("the a an this that these those some i we you it there what who")
#: "I'm parched": a need names the ontology class of what would meet it.
NEEDS: dict[str, str] = {
    "thirsty": "drink", "parched": "drink", "dehydrated": "drink",
    "hungry": "food", "starving": "food", "peckish": "food", "famished": "food", "ravenous": "food",
}  # fmt: skip
#: "something to eat" is food, "something to cut this with" a cutting tool: what a thing is for names
#: its kind (the ontology's classes "food", "drink"; the lexicon file's general names).
PURPOSES: dict[str, Words] = {
    "eat": ("food",), "drink": ("drink",), "cut": ("cutting", "tool"), "write": ("writing", "tool"),
    "draw": ("writing", "tool"), "wipe": ("cleaning", "cloth"), "clean": ("cleaning", "cloth"),
    "dry": ("cleaning", "cloth"), "read": ("reading", "matter"), "wear": ("clothing",), "sit": ("seat",),
}  # fmt: skip


def purpose(words: Words) -> Words | None:
    """The kind of thing "to eat", "to cut this with" (the words after "something") name, if any."""
    return PURPOSES.get(words[1]) if len(words) > 1 and words[0] == "to" else None
INTENSIFIERS = word_set("so very really absolutely quite a bit little totally getting rather pretty bloody")
#: What follows "do" in a request ("do the dishes", "do some exercise"); anything else after "do"
#: is a yes/no question ("do you like music", "do robots ever get tired").
DONE = word_set("the a an some my your our this that these those exercise exercises yoga stretches")
#: "the butter goes back in the fridge", "these should go on the top shelf": where a thing is to be put.
GOES = phrases(
    "goes|go|belongs|belong|lives|live|should go|can go|needs to go|need to go|has to go|have to go|must go|"
    "should be put|needs to be put|has to be put|wants to go"
)
GOES_PARTICLES = word_set("back away over up down")
#: Verbs of motion a terse request says a place after with no preposition ("go workstand").
TERSE_MOTION = word_set("go come walk move head drive")
#: Prepositions of a request with no verb that puts a thing somewhere ("sunflowers into tall vase").
TERSE_PLACING = word_set("into onto on in")
EVERYONE = frozenset(phrases("everyone|everybody|all|them all|people"))
#: Words of "stop whatever you are doing" that do not name the activity.
STOP_FILLER = word_set(
    "what you are doing it that this everything all the current activity task now please immediately "
    "right there your whatever am is enough shut up"
)
#: Words of "play a game with me" that do not name the activity.
ACTIVITY_FILLER = word_set("the a an some with me us of")
#: Actions the robot has no intent for: a part of a compound request with one of these is kept in
#: the reply ("I can't find the newspaper myself"), never silently dropped.
#: States a request asks a thing to be brought into ("get it ready", "have the room sorted"): no
#: intent of the robot's says it, whatever the verb, and the part is kept in the reply.
RESULTS = word_set("ready sorted done prepared finished organised organized tidied cleaned")
NO_INTENT_VERBS = word_set(
    "find search look open close turn switch remove control check wait stay watch heat boil pour fill "
    "empty plug unplug lock unlock answer call fix feed follow serve see"
)
