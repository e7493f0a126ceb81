"""is_graphs BIM tools: IFC -> A-Graph conversion (see docs/agraph_format.md)."""

CONVERTER_VERSION = "7"
