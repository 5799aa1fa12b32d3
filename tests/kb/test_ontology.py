"""The ORO-compatible ontology shipped in `ontologies/oro.ttl`.

Checks the vocabulary contract of kb-compat §6 (terms, characteristics, individuals, labels), that
only the OWL constructs situated's reasoner supports are used, and, with owlrl as the reference
semantics, the inferences robot queries rely on (§7.2, §7.3).
"""

from __future__ import annotations

from importlib.resources import files

import owlrl
import pytest
from rdflib import BNode, Graph, Literal, Namespace, URIRef
from rdflib.collection import Collection
from rdflib.namespace import FOAF, OWL, RDF, RDFS, XSD
from rdflib.term import Node

ORO = Namespace("http://kb.openrobots.org#")
CYC = Namespace("http://sw.opencyc.org/concept/")
DBR = Namespace("https://dbpedia.org/resource/")
DCTERMS = Namespace("http://purl.org/dc/terms/")
OWLRL_ERRORS = Namespace("http://www.daml.org/2002/03/agents/agent-ont#")
EX = Namespace("http://example.org/test#")
XSD_NS = "http://www.w3.org/2001/XMLSchema#"

PREFIXES = {"": str(ORO), "cyc": str(CYC), "dbr": str(DBR), "foaf": str(FOAF), "ex": str(EX)}
PREFIXES.update(owl=str(OWL), rdf=str(RDF), rdfs=str(RDFS))
TURTLE_PREFIXES = "".join(f"@prefix {p}: <{ns}> .\n" for p, ns in PREFIXES.items())


def curies(text: str) -> list[URIRef]:
    """`Human cyc:Food <http://...>` -> IRIs; a bare name is an ORO term."""
    terms = []
    for token in text.split():
        if token.startswith("<"):
            terms.append(URIRef(token[1:-1]))
        else:
            prefix, sep, local = token.partition(":")
            terms.append(URIRef(PREFIXES[prefix] + local) if sep else ORO[token])
    return terms


def short_id(value: object) -> str:
    """Readable parametrize ids: `dbr:Cup`, `ex:a isOn ex:b`."""
    if isinstance(value, tuple):
        return " ".join(short_id(v) for v in value)
    if isinstance(value, URIRef):
        for prefix, namespace in PREFIXES.items():
            if value.startswith(namespace):
                return (f"{prefix}:" if prefix else "") + value[len(namespace) :]
    return str(value)


def turtle(text: str) -> Graph:
    return Graph().parse(data=TURTLE_PREFIXES + text, format="turtle")


HTTP_DBPEDIA_TERMS = {
    URIRef("http://dbpedia.org/ontology/Plant"),
    URIRef("http://dbpedia.org/property/color"),
    URIRef("http://dbpedia.org/property/name"),
}
ORO_FUNCTIONAL = set(
    curies(
        "canBeManipulated hasCharacteristicDimension hasCharacteristicWeight isDesired isHolder isMovable "
        "isMoving isPerceived isReachable isSitting isTraversable isVisible preferredName hasColor "
        "hasEngagementLevel hasInLeftHand hasInRightHand hasPosture hasShape hasSize isLocated "
        "mainColorOfObject"
    )
)
ORO_SYMMETRIC = set(curies("cyc:farFrom cyc:near isNextTo isSharedSituation jointEngagementWith"))
ORO_TRANSITIVE = set(curies("behind inFrontOf leftOf rightOf"))
ORO_INVERSE_PAIRS = {
    frozenset((a, b))
    for a, _, b in turtle("""
:behind owl:inverseOf :inFrontOf .  :canBePerformedBy owl:inverseOf :canPerform .
:contains owl:inverseOf :isContainedIn .  :currentlyDoes owl:inverseOf :currentlyDoneBy .
:experiences owl:inverseOf :isExperienced .  :focusesOn owl:inverseOf :isFocusOf .
:isAbove owl:inverseOf :isBelow .  :isAt owl:inverseOf :placeOf .  :leftOf owl:inverseOf :rightOf .
""")
}

# The terms of kb-compat §6.2-6.4 and §6.7-6.8, by kind.
EXPECTED_DECLARATIONS = {
    OWL.Class: curies(
        "Agent EmbodiedAgent Human Robot Avatar BodyPart Eye Head Torso Hand LeftHand RightHand Location "
        "Artifact Object Container GraspableObject Place PhysicalSupport Floor Wall Ceilling Obstacle "
        "Opening Window RegionOfSpace SpaceChunk Zone ZoneOfInterest ZoneOfAction ZoneOfInteraction "
        "FieldOfView Point Shelf Tableware Bottle Glass Situation EngagementSituation EngagementLevel "
        "EmotionalState JointAttentionSituation Task Manipulation Give Pick Put Release Cover Uncover "
        "Navigation Interaction Greeting EligibleAction Idling Rest Posture Shape Size ActiveConcept Box "
        "Cardboardbox StorageBox Toolbox Toy ToyCube GameArtifact Remote Trashbin Cloth Jacket Placemat "
        "VisualMark NonAlcoholicBeverage TimeInterval ContinuousTimeInterval TimePoint TaskPlan "
        "cyc:SpatialThing cyc:SpatialThing-Localized cyc:EnduringThing-Localized cyc:PartiallyTangible "
        "cyc:SolidTangibleThing cyc:FluidTangibleThing cyc:SpaceRegion cyc:FurniturePiece "
        "cyc:Object-SupportingFurniture cyc:Table-PieceOfFurniture cyc:Sofa-PieceOfFurniture "
        "cyc:Chair-PieceOfFurniture cyc:ArmChair cyc:CellularTelephone cyc:Food cyc:FoodOrDrink "
        "cyc:EdibleStuff cyc:Plant cyc:Situation cyc:Plan-ExpectedSituationType cyc:TemporalThing "
        "cyc:StaticSituation cyc:Event cyc:Action cyc:PurposefulAction cyc:Resting-Relaxing cyc:Color "
        "cyc:Hand cyc:Can cyc:Tray cyc:Drink cyc:AlcoholicBeverage cyc:SoftDrink cyc:AppleJuice "
        "cyc:OrangeJuice cyc:Beer cyc:Wine dbr:Cup dbr:Book dbr:Smartphone dbr:Apple dbr:Pear dbr:Fruit "
        "dbr:Table_(furniture) dbr:Coffee_table dbr:Couch dbr:Ornamental_plant dbr:Shelf_(storage) dbr:Bed "
        "dbr:Plant dbr:Chair dbr:Armchair_(furniture) dbr:Bottle dbr:Glass_(drinkware) dbr:Waste_container "
        "dbr:Tableware dbr:Fork dbr:Knife dbr:Spoon dbr:Kitchen_utensil foaf:Agent foaf:Person "
        "<http://dbpedia.org/ontology/Plant>"
    ),
    OWL.ObjectProperty: curies(
        "sees looksAt focusesOn isFocusOf pointsAt isAt placeOf isIn isOn isAbove isBelow isNextTo "
        "hasRelativePosition agentRelativeProperty behind inFrontOf leftOf rightOf contains isContainedIn "
        "belongsTo isLocated hasInHand hasInLeftHand hasInRightHand holds hasBodyPart desires experiences "
        "isExperienced staticSituationInvolves involves hasPosture currentlyPerforms currentlyDoes "
        "currentlyDoneBy canPerform canBePerformedBy isAbleTo canUndertakeNow hasEngagementLevel "
        "jointEngagementWith isSharedSituation actsOnObject hasThematicRoleRelationWith hasGoal receivedBy "
        "objectOfAction purposeOfAction recipientOfAction actionInvolves hasColor hasFeature "
        "mainColorOfObject hasShape hasSize after after-Underspecified startsAfterEndingOf startingPoint "
        "endingPoint duration temporallyRelated bringsToStaticSituation taskOfPlan "
        "hasCharacteristicLocation reaches isEngagedWith wants likes engagementLevel cyc:pointingToward "
        "cyc:objectFoundInLocation cyc:above-Generally cyc:near cyc:farFrom cyc:behind-Generally "
        "cyc:inFrontOf-Generally cyc:holds-Underspecified cyc:doneBy cyc:performedBy cyc:bodilyDoer "
        "cyc:above_Touching foaf:knows <http://dbpedia.org/property/color>"
    ),
    OWL.DatatypeProperty: curies(
        "isPerceived isVisible isMoving isTraversable isInFieldOfView isMovable isHolder isReachable "
        "canBeManipulated hasCharacteristicDimension hasCharacteristicWeight isSitting isDesired hasName "
        "preferredName foaf:name <http://dbpedia.org/property/name>"
    ),
    OWL.AnnotationProperty: curies("openCycUri question interrogative"),
}

# K14: labels of the terms a dialogue names (a subset of what the ontology must contain).
EXPECTED_LABELS = turtle("""
dbr:Cup rdfs:label "cup"@en .  dbr:Apple rdfs:label "apple"@en .  dbr:Pear rdfs:label "pear"@en .
dbr:Fruit rdfs:label "fruit"@en .  dbr:Book rdfs:label "book"@en .  dbr:Bed rdfs:label "bed"@en .
dbr:Smartphone rdfs:label "smartphone"@en , "phone"@en .  dbr:Table_\\(furniture\\) rdfs:label "table"@en .
dbr:Couch rdfs:label "sofa"@en , "couch"@en .  dbr:Coffee_table rdfs:label "coffee table"@en .
dbr:Ornamental_plant rdfs:label "plant"@en .  dbr:Shelf_\\(storage\\) rdfs:label "shelf"@en .
dbr:Chair rdfs:label "chair"@en .  dbr:Armchair_\\(furniture\\) rdfs:label "armchair"@en .
dbr:Glass_\\(drinkware\\) rdfs:label "glass"@en .  dbr:Waste_container rdfs:label "waste container"@en .
dbr:Fork rdfs:label "fork"@en .  :Human rdfs:label "person"@en , "human"@en .  :Robot rdfs:label "robot"@en .
:ZoneOfInterest rdfs:label "zone"@en , "room"@en .  :Remote rdfs:label "remote"@en , "remote control"@en .
:Trashbin rdfs:label "trash bin"@en .  :Artifact rdfs:label "artifact"@en , "object"@en .
:Object rdfs:label "object"@en .  :EmbodiedAgent rdfs:label "embodied agent"@en .
foaf:Agent rdfs:label "agent"@en .  cyc:FurniturePiece rdfs:label "furniture"@en .
cyc:Sofa-PieceOfFurniture rdfs:label "couch"@en , "sofa"@en .  cyc:Color rdfs:label "colour"@en .
cyc:SpatialThing-Localized rdfs:label "location"@en .  cyc:CellularTelephone rdfs:label "mobile phone"@en .
:sees rdfs:label "sees"@en , "see"@en , "voit"@fr .  :looksAt rdfs:label "looks at"@en .
:isIn rdfs:label "is in"@en , "am in"@en , "are in"@en , "est dans"@fr .  :isOn rdfs:label "is on"@en .
:isAt rdfs:label "is at"@en , "am at"@en .  :isNextTo rdfs:label "is next to"@en , "am next to"@en .
:isBelow rdfs:label "is under"@en .  :isAbleTo rdfs:label "can"@en , "is able to"@en .
:isEngagedWith rdfs:label "is engaged with"@en .  :wants rdfs:label "wants"@en , "want"@en .
:likes rdfs:label "likes"@en , "like"@en .  :engagementLevel rdfs:label "engagement level"@en .
:myself rdfs:label "myself"@en , "moi-même"@fr .
""")

ALLOWED_OWL_TERMS = set(
    curies(
        "owl:Ontology owl:Class owl:Restriction owl:ObjectProperty owl:DatatypeProperty "
        "owl:AnnotationProperty owl:SymmetricProperty owl:TransitiveProperty owl:FunctionalProperty "
        "owl:AllDisjointClasses owl:AllDifferent owl:NamedIndividual owl:equivalentClass owl:intersectionOf "
        "owl:unionOf owl:onProperty owl:hasValue owl:equivalentProperty owl:inverseOf owl:disjointWith "
        "owl:members owl:versionInfo"
    )
)
ALLOWED_PREDICATES = ALLOWED_OWL_TERMS | set(
    curies("rdf:type rdf:first rdf:rest rdfs:subClassOf rdfs:subPropertyOf rdfs:domain rdfs:range")
    + curies("rdfs:label rdfs:comment")
)

ABOX = turtle("""
ex:cup a dbr:Cup .  ex:table a dbr:Table_\\(furniture\\) .  ex:coffee_table a dbr:Coffee_table .
ex:shelf a dbr:Shelf_\\(storage\\) .  ex:couch a dbr:Couch .  ex:phone a dbr:Smartphone .
ex:book a dbr:Book .  ex:apple a dbr:Apple .  ex:plant a dbr:Ornamental_plant .  ex:fork a dbr:Fork .
ex:kitchen a :ZoneOfInterest .  ex:wall a :Wall .
ex:person a :Human ; :looksAt ex:cup ; :isEngagedWith :myself ; :wants ex:cup ; :engagementLevel :engaged .
ex:a :isOn ex:b .  ex:x :leftOf ex:y .  ex:y :leftOf ex:z .  ex:c :isIn ex:t .  ex:t :isIn ex:k .
""")

# What the OWL RL closure of ontology + ABOX must contain (§7.2, §7.3) ...
ENTAILED = turtle("""
ex:cup a :Tableware , :Artifact , cyc:PartiallyTangible ; :isMovable true .
ex:table a cyc:FurniturePiece , :Artifact , :PhysicalSupport , :Place , cyc:Table-PieceOfFurniture ;
    :isHolder true .
ex:coffee_table a cyc:FurniturePiece .
ex:shelf a :Shelf , :PhysicalSupport ; :isHolder true .
ex:couch a cyc:Sofa-PieceOfFurniture , :Artifact .
ex:phone a cyc:CellularTelephone , :Artifact .
ex:book a :Artifact , cyc:SolidTangibleThing ; :isMovable true .
ex:fork a :Tableware .
ex:person a :Agent , foaf:Agent , foaf:Person , :EmbodiedAgent .
ex:apple a dbr:Fruit , cyc:Food , cyc:Plant , cyc:PartiallyTangible .
ex:plant a cyc:Plant .
ex:kitchen a cyc:SpaceRegion .
ex:wall a :PhysicalSupport .
ex:a :isAt ex:b .  ex:b :placeOf ex:a .  ex:x :leftOf ex:z .  ex:z :rightOf ex:x .  ex:c :isAt ex:t .
:myself :isEngagedWith ex:person .
""")

# ... and what it must not: no isIn/isAt transitivity, looksAt is not sees, wants is not desires.
NOT_ENTAILED = turtle("""
ex:c :isIn ex:k ; :isAt ex:k .
ex:person :sees ex:cup .
ex:cup a cyc:Situation , :PhysicalSupport .
ex:couch :isHolder true .
""")


HasValue = tuple[Node | None, Node | None]


def load_ontology() -> Graph:
    source = files("ontologies") / "oro.ttl"
    return Graph().parse(data=source.read_text(encoding="utf-8"), format="turtle")


@pytest.fixture(scope="module")
def onto() -> Graph:
    return load_ontology()


@pytest.fixture(scope="module")
def closure(onto: Graph) -> Graph:
    graph = Graph()
    graph += onto
    graph += ABOX
    owlrl.DeductiveClosure(owlrl.OWLRL_Semantics).expand(graph)
    return graph


def subjects_typed(graph: Graph, cls: URIRef) -> set[Node]:
    return set(graph.subjects(RDF.type, cls))


def list_members(graph: Graph, subject: Node, pred: URIRef) -> list[Node]:
    head = graph.value(subject, pred)
    assert head is not None, f"{subject} has no {pred}"
    return list(Collection(graph, head))


def en_labels(graph: Graph, term: URIRef) -> set[str]:
    return {str(o) for o in graph.objects(term, RDFS.label) if isinstance(o, Literal) and o.language == "en"}


# --- identity and declarations ---------------------------------------------------------------------


def test_parses_with_ontology_header(onto: Graph) -> None:
    header = URIRef("http://kb.openrobots.org")
    assert (header, RDF.type, OWL.Ontology) in onto
    for pred in (DCTERMS.title, DCTERMS.creator, DCTERMS.license):
        assert onto.value(header, pred) is not None
    assert "situated's own ORO-compatible ontology" in str(onto.value(header, RDFS.comment))


def test_dbpedia_terms_use_https_except_the_three_http_ones(onto: Graph) -> None:
    used = {t for triple in onto for t in triple if isinstance(t, URIRef)}
    assert {t for t in used if t.startswith("http://dbpedia.org/")} == HTTP_DBPEDIA_TERMS


@pytest.mark.parametrize(("kind", "expected"), EXPECTED_DECLARATIONS.items(), ids=short_id)
def test_terms_declared(onto: Graph, kind: URIRef, expected: list[URIRef]) -> None:
    assert not set(expected) - subjects_typed(onto, kind)


def test_every_referenced_class_and_property_is_declared(onto: Graph) -> None:
    """Catches misspelt names: a typo would silently create a new, unconnected term."""
    class_refs: set[Node] = set(onto.objects(None, RDFS.domain))
    for pred in (RDFS.subClassOf, OWL.equivalentClass, OWL.disjointWith):
        class_refs |= set(onto.subjects(pred, None)) | set(onto.objects(None, pred))
    class_refs |= {o for o in onto.objects(None, RDFS.range) if not str(o).startswith(XSD_NS)}
    for pred in (OWL.unionOf, OWL.intersectionOf):
        for head in onto.objects(None, pred):
            class_refs |= set(Collection(onto, head))
    for group in subjects_typed(onto, OWL.AllDisjointClasses):
        class_refs |= set(list_members(onto, group, OWL.members))
    for individual in subjects_typed(onto, OWL.NamedIndividual):
        class_refs |= set(onto.objects(individual, RDF.type)) - {OWL.NamedIndividual}
    assert not class_refs - subjects_typed(onto, OWL.Class) - subjects_typed(onto, OWL.Restriction)

    property_refs: set[Node] = set(onto.objects(None, OWL.onProperty))
    for pred in (RDFS.subPropertyOf, OWL.inverseOf, OWL.equivalentProperty):
        property_refs |= set(onto.subjects(pred, None)) | set(onto.objects(None, pred))
    properties = subjects_typed(onto, OWL.ObjectProperty) | subjects_typed(onto, OWL.DatatypeProperty)
    assert not property_refs - properties


# --- characteristics (§6.5) -----------------------------------------------------------------------


#: Minted functional properties: the engagement level, and the dialogue memory's single values.
MINTED_FUNCTIONAL = {ORO.engagementLevel, ORO.toldAt, ORO.toldAs, ORO.lastSpokeAt, ORO.dialogueSummary}


def test_functional_properties_are_oros_plus_the_minted_ones(onto: Graph) -> None:
    assert len(ORO_FUNCTIONAL) == 22
    assert subjects_typed(onto, OWL.FunctionalProperty) == ORO_FUNCTIONAL | MINTED_FUNCTIONAL


def test_symmetric_properties_are_oros_plus_is_engaged_with(onto: Graph) -> None:
    assert subjects_typed(onto, OWL.SymmetricProperty) == ORO_SYMMETRIC | {ORO.isEngagedWith}


def test_exactly_the_four_transitive_properties(onto: Graph) -> None:
    assert subjects_typed(onto, OWL.TransitiveProperty) == ORO_TRANSITIVE


def test_exactly_the_nine_inverse_pairs(onto: Graph) -> None:
    assert {frozenset((s, o)) for s, o in onto.subject_objects(OWL.inverseOf)} == ORO_INVERSE_PAIRS


def test_minted_properties_signatures(onto: Graph) -> None:
    def signature(prop: URIRef) -> tuple[Node | None, Node | None]:
        return onto.value(prop, RDFS.domain), onto.value(prop, RDFS.range)

    assert (ORO.wants, RDFS.subPropertyOf, ORO.desires) not in onto
    assert signature(ORO.wants) == (FOAF.Agent, None)
    assert signature(ORO.likes) == (None, None)
    assert signature(ORO.dislikes) == (None, None)
    assert signature(ORO.toldBy) == (ORO.ToldFact, FOAF.Agent)
    assert signature(ORO.toldAt) == (ORO.ToldFact, XSD.dateTime)
    assert signature(ORO.lastSpokeAt) == (FOAF.Agent, XSD.dateTime)
    assert signature(ORO.dialogueSummary) == (FOAF.Agent, XSD.string)
    assert signature(ORO.isEngagedWith) == (FOAF.Agent, FOAF.Agent)
    assert "jointEngagementWith" in str(onto.value(ORO.isEngagedWith, RDFS.comment))
    assert signature(ORO.engagementLevel) == (FOAF.Agent, ORO.EngagementLevel)
    assert signature(ORO.hasEngagementLevel) == (ORO.EngagementSituation, ORO.EngagementLevel)


def test_disjointness(onto: Graph) -> None:
    groups = {
        frozenset(list_members(onto, g, OWL.members)) for g in subjects_typed(onto, OWL.AllDisjointClasses)
    }
    assert groups == {
        frozenset(curies("Artifact Ceilling Floor Wall")),
        frozenset(curies("Artifact VisualMark foaf:Agent")),
        frozenset(curies("Bottle Glass dbr:Cup")),
        frozenset(curies("Situation cyc:Color cyc:SpatialThing")),
    }
    assert (ORO.Human, OWL.disjointWith, ORO.Robot) in onto
    assert (CYC.StaticSituation, OWL.disjointWith, CYC.Event) in onto


# --- individuals (§6.6) ---------------------------------------------------------------------------


def test_myself(onto: Graph) -> None:
    assert (ORO.myself, RDF.type, FOAF.Agent) in onto
    labels = set(onto.objects(ORO.myself, RDFS.label))
    assert {Literal("myself", lang="en"), Literal("moi-même", lang="fr")} <= labels


def test_individuals_and_all_different_groups(onto: Graph) -> None:
    colours = set(curies("black blue gray green orange pink red violet white yellow"))
    shapes = set(curies("boxShape cylinderShape sphereShape"))
    postures = set(curies("sitting standing"))
    assert subjects_typed(onto, CYC.Color) == colours
    assert subjects_typed(onto, ORO.Shape) == shapes
    assert subjects_typed(onto, ORO.Posture) == postures
    assert subjects_typed(onto, ORO.EngagementLevel) == set(curies("engaging engaged disengaging disengaged"))
    assert (ORO.current_world_state, RDF.type, CYC.StaticSituation) in onto
    assert (ORO.unknownLocation, RDF.type, CYC.SpatialThing) in onto
    groups = {frozenset(list_members(onto, g, OWL.members)) for g in subjects_typed(onto, OWL.AllDifferent)}
    assert groups == {frozenset(colours), frozenset(shapes), frozenset(postures)}


# --- labels (K14) ---------------------------------------------------------------------------------


@pytest.mark.parametrize("triple", sorted(EXPECTED_LABELS), ids=short_id)
def test_labels(onto: Graph, triple: tuple[Node, Node, Node]) -> None:
    assert triple in onto


def test_every_label_has_a_language_tag(onto: Graph) -> None:
    assert not [(s, o) for s, o in onto.subject_objects(RDFS.label) if not getattr(o, "language", None)]


def test_every_named_class_property_and_individual_has_an_english_label(onto: Graph) -> None:
    kinds = (OWL.Class, OWL.ObjectProperty, OWL.DatatypeProperty, OWL.AnnotationProperty, OWL.NamedIndividual)
    named = {s for kind in kinds for s in subjects_typed(onto, kind) if isinstance(s, URIRef)}
    named -= {DCTERMS.title, DCTERMS.creator, DCTERMS.license}
    assert not {term for term in named if not en_labels(onto, term)}


# --- only the supported OWL subset ----------------------------------------------------------------


def test_only_supported_constructs(onto: Graph) -> None:
    owl_terms = {t for triple in onto for t in triple if isinstance(t, URIRef) and t.startswith(str(OWL))}
    assert owl_terms <= ALLOWED_OWL_TERMS
    assert set(onto.predicates()) <= ALLOWED_PREDICATES | subjects_typed(onto, OWL.AnnotationProperty)

    restrictions = subjects_typed(onto, OWL.Restriction)
    for restriction in restrictions:
        assert set(onto.predicates(restriction)) == {RDF.type, OWL.onProperty, OWL.hasValue}
    for head in onto.objects(None, OWL.intersectionOf):
        assert all(isinstance(m, URIRef) or m in restrictions for m in Collection(onto, head))
    for head in onto.objects(None, OWL.unionOf):
        assert all(isinstance(m, URIRef) for m in Collection(onto, head))


def test_anonymous_class_expressions(onto: Graph) -> None:
    """The intersections, unions and hasValue restrictions stated in §6.2 and §6.7."""

    def has_value(node: Node) -> HasValue:
        return onto.value(node, OWL.onProperty), onto.value(node, OWL.hasValue)

    def expressions(cls: URIRef, pred: URIRef, kind: URIRef) -> list[list[Node]]:
        anonymous = [e for e in onto.objects(cls, pred) if isinstance(e, BNode)]
        return [list_members(onto, e, kind) for e in anonymous if onto.value(e, kind) is not None]

    def intersection(cls: URIRef, pred: URIRef = OWL.equivalentClass) -> tuple[set[Node], set[HasValue]]:
        (members,) = expressions(cls, pred, OWL.intersectionOf)
        return {m for m in members if isinstance(m, URIRef)}, {
            has_value(m) for m in members if isinstance(m, BNode)
        }

    true, false = Literal(True), Literal(False)
    holder = {(ORO.isHolder, true)}
    assert intersection(CYC["Object-SupportingFurniture"]) == ({CYC.FurniturePiece}, holder)
    assert intersection(ORO.PhysicalSupport) == ({CYC.PartiallyTangible}, holder)
    assert intersection(ORO.Obstacle) == ({CYC["EnduringThing-Localized"]}, {(ORO.isTraversable, false)})
    assert intersection(DBR.Book, RDFS.subClassOf) == ({ORO.Artifact}, {(ORO.isMovable, true)})
    tableware = {has_value(e) for e in onto.objects(ORO.Tableware, RDFS.subClassOf) if isinstance(e, BNode)}
    assert tableware == {(ORO.isMovable, true)}

    def union(cls: URIRef) -> set[Node]:
        (members,) = expressions(cls, OWL.equivalentClass, OWL.unionOf)
        return set(members)

    assert union(ORO.EmbodiedAgent) == {ORO.Human, ORO.Robot}
    assert union(FOAF.Agent) == {ORO.Avatar, ORO.Human, ORO.Robot}
    assert union(CYC.Hand) == {ORO.LeftHand, ORO.RightHand}


# --- OWL RL closure (owlrl is the reference semantics) --------------------------------------------


def test_closure_is_consistent(closure: Graph) -> None:
    assert not [str(m) for m in closure.objects(None, OWLRL_ERRORS.error)]


@pytest.mark.parametrize("triple", sorted(ENTAILED), ids=short_id)
def test_closure_entails(closure: Graph, triple: tuple[Node, Node, Node]) -> None:
    assert triple in closure


@pytest.mark.parametrize("triple", sorted(NOT_ENTAILED), ids=short_id)
def test_closure_does_not_entail(closure: Graph, triple: tuple[Node, Node, Node]) -> None:
    assert triple not in closure
