"""Parses an XML (or XHTML) file with Python's xml.etree and prints the element tree as JSON:
{"tag", "attrib", "text", "children"} with namespaces stripped from tags. An independent
well-formedness check and structure reader for the report tests; exits 1 on a parse error."""
import json
import sys
import xml.etree.ElementTree as ET


def node(element):
    tag = element.tag.split('}', 1)[-1]
    return {
        "tag": tag,
        "attrib": {k.split('}', 1)[-1]: v for k, v in element.attrib.items()},
        "text": "".join(element.itertext()),
        "children": [node(child) for child in element],
    }


try:
    root = ET.parse(sys.argv[1]).getroot()
except ET.ParseError as error:
    print(f"{sys.argv[1]}: not well-formed: {error}", file=sys.stderr)
    sys.exit(1)
print(json.dumps(node(root)))
