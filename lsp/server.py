"""`logixst lsp`: the protocol glue between pygls and the protocol-free features.

Every handler asks the Workspace for the document's analysis and turns the features' plain
data into lsprotocol objects. A failure inside a feature never stops the server: it is
logged with window/logMessage and the request gets an empty answer.
"""

from __future__ import annotations

import asyncio
import gc
import re
import traceback
from collections.abc import Callable
from typing import Any, TypeVar

from lsprotocol import types as t
from pygls.exceptions import JsonRpcException
from pygls.lsp.server import LanguageServer
from pygls.protocol import LanguageServerProtocol
from pygls.workspace.text_document import TextDocument

from interpreter.syntax import nodes as n

from .features import completion as comp
from .features.actions import actions
from .features.diagnostics import to_editor
from .features.hover import hover
from .features.navigation import Location, RenameRefused, definition, references, rename
from .features.signature import Signature, signature
from .features.symbols import Symbol, document_symbols, folding_ranges
from .features.tokens import LEGEND, encode, semantic_tokens
from .lines import find_line, line_start, remember
from .workspace import Workspace, language_of, uri_to_path

DEBOUNCE_S = 0.05  # diagnostics after typing pauses this long
VERSION = "0.1.0"

R = TypeVar("R")


class _Ignored:
    """A message already answered with an error: pygls' dispatcher skips it (unknown version)."""

    jsonrpc = "ignored"

    def __repr__(self) -> str:  # pygls logs it as an unknown message
        return "(a request already answered with an error)"


class LogixProtocol(LanguageServerProtocol):
    """Answers a request whose parameters do not deserialise (a negative position, a string
    where an object belongs) with a JSON-RPC error, as the protocol requires. pygls raises
    while decoding and never answers: the editor would wait on that request forever (found
    by tests/fuzz/test_lsp_fuzz.py)."""

    def structure_message(self, data: dict[str, Any]) -> Any:
        try:
            return super().structure_message(data)
        except JsonRpcException as exc:
            if "id" in data and "method" in data:
                self._send_response(data["id"], error=exc.to_response_error())
                return _Ignored()
            raise


class LogixServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__(
            "logixst",
            VERSION,
            text_document_sync_kind=t.TextDocumentSyncKind.Incremental,
            protocol_cls=LogixProtocol,
        )
        self.docs = Workspace()
        self.pending: dict[str, asyncio.TimerHandle] = {}
        self.refusals: dict[str, str] = {}  # uri -> the reason told for not analysing it

    def log(self, message: str, kind: t.MessageType = t.MessageType.Log) -> None:
        try:
            self.window_log_message(t.LogMessageParams(kind, message))
        except Exception:  # noqa: BLE001 - logging must never fail a request
            pass

    def sync(self, uri: str) -> bool:
        """Copy pygls' current text of `uri` into our workspace; False when it is not open."""
        try:
            doc = self.workspace.get_text_document(uri)
            text = doc.source
        except Exception:  # noqa: BLE001
            return False
        if uri in self.docs.documents:
            self.docs.change(uri, text, doc.version or 0)
        else:
            self.docs.open(uri, text, doc.version or 0)
        return True

    def publish(self, uri: str) -> None:
        self.pending.pop(uri, None)
        an = guarded(self, None, lambda: _collector_paused(lambda: self.docs.analyse(uri)))
        if an is None:  # closed, or text `check` would refuse as input: nothing to show
            doc = self.docs.get(uri)
            if doc is not None:
                # the reason first: an editor (or test) that reacts to the empty diagnostics
                # has already been told why (messages arrive in the order sent)
                self.tell_refusal(uri)
                self.text_document_publish_diagnostics(
                    t.PublishDiagnosticsParams(uri=uri, diagnostics=[], version=doc.version)
                )
            return
        self.refusals.pop(uri, None)
        diags = []
        for d in an.diagnostics:
            e = to_editor(d)
            diags.append(
                t.Diagnostic(
                    range=t.Range(
                        t.Position(e.line, e.character), t.Position(e.end_line, e.end_character)
                    ),
                    message=e.message,
                    severity=t.DiagnosticSeverity(e.severity),
                    code=e.code,
                    code_description=t.CodeDescription(href=e.href),
                    source="logixst",
                )
            )
        self.text_document_publish_diagnostics(
            t.PublishDiagnosticsParams(uri=uri, diagnostics=diags, version=an.document.version)
        )

    def tell_refusal(self, uri: str) -> None:
        """Say once (until the reason changes) why a document gets no analysis, as `check`
        would refuse the file: a limit is enforced with a message (docs/limits.md)."""
        why = self.docs.refused(uri)
        if why is not None and self.refusals.get(uri) != why:
            self.refusals[uri] = why
            self.window_show_message(t.ShowMessageParams(t.MessageType.Warning, why))

    def schedule(self, uri: str) -> None:
        old = self.pending.pop(uri, None)
        if old is not None:
            old.cancel()
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            self.publish(uri)
            return
        self.pending[uri] = loop.call_later(DEBOUNCE_S, self.publish, uri)


# Line breaks pygls' own line splitting knows beyond "\n" (str.splitlines): a text holding
# any is left to pygls' slow but faithful change handling.
_OTHER_BREAKS = re.compile("[\r\x0b\x0c\x1c-\x1e\x85\u2028\u2029]")


class FastDocument(TextDocument):
    """pygls' document, with an incremental change spliced into the text: pygls rebuilds the
    text line by line (35 ms per keystroke on a 2 MB export). Positions are converted by
    pygls' own codec on the edited lines only, so the result is the same text."""

    _plain: bool | None = None  # the text has no other line break (known at the first edit)

    def _apply_incremental_change(self, change: t.TextDocumentContentChangePartial) -> None:
        if self._plain is None:
            self._plain = _OTHER_BREAKS.search(self.source) is None
        if not self._plain or _OTHER_BREAKS.search(change.text):
            super()._apply_incremental_change(change)
            self._plain = _OTHER_BREAKS.search(self.source) is None
            return
        text = self.source
        start = self._offset(text, change.range.start)
        end = max(start, self._offset(text, change.range.end))
        line_begin = find_line(text, change.range.start.line)
        self._source = text[:start] + change.text + text[end:]
        if line_begin is not None:  # the edit is after its start: the next lookup starts there
            remember(self._source, change.range.start.line, line_begin)

    def _offset(self, text: str, p: t.Position) -> int:
        begin = line_start(text, p.line)
        if begin >= len(text):
            return len(text)  # past the last line: at the end, as pygls appends there
        nl = text.find("\n", begin)
        end = len(text) if nl < 0 else nl
        line = text[begin:end]
        codec = self._position_codec
        if p.character >= codec.client_num_units(line):
            return end  # past the line's end: at its end (LSP)
        return (
            begin + codec.position_from_client_units([line], t.Position(0, p.character)).character
        )


def _fast_documents(ls: LanguageServer) -> None:
    """Make pygls' workspace create FastDocuments (it is made at initialize)."""
    ws = ls.workspace

    def create(
        doc_uri: str,
        source: str | None = None,
        version: int | None = None,
        language_id: str | None = None,
    ) -> TextDocument:
        return FastDocument(
            doc_uri,
            source=source,
            version=version,
            language_id=language_id,
            sync_kind=ws._sync_kind,
            position_codec=ws.position_codec,
        )

    ws._create_text_document = create  # type: ignore[method-assign]


def _collector_paused(fn: Callable[[], R]) -> R:
    """Analysis allocates many small objects and no cycles worth collecting: the cyclic
    collector's passes would cost a third of the time (as in runtime/loader.gc_paused).

    After an analysis everything alive is frozen out of the collector's sight (gc.freeze):
    an export's analysis is some 600,000 objects, and once they are old a full collection
    of them takes about a second, which would land inside some later keystroke's request.
    What was frozen is still freed by reference counting when it is dropped (an analysis
    holds no cycles: xml_reader breaks its parser's). Requests answered from the cache do
    not freeze, so their short-lived cycles stay collectable (decision 0119)."""
    enabled = gc.isenabled()
    before = server.docs.analyses
    gc.disable()
    try:
        return fn()
    finally:
        if enabled:
            if server.docs.analyses != before:
                gc.freeze()
            gc.enable()


def guarded(server: LogixServer, empty: R, fn: Callable[[], R]) -> R:
    """Run a feature; on any failure log it and answer `empty` (the server keeps going)."""
    try:
        return fn()
    except Exception:  # noqa: BLE001 - a feature bug must not take the server down
        server.log(f"logixst: internal error\n{traceback.format_exc()}", t.MessageType.Error)
        return empty


server = LogixServer()


def _analysed(uri: str, fresh: bool = False):  # type: ignore[no-untyped-def]
    """The document's analysis: `fresh` for navigation (exact spans), else the latest one."""
    if uri not in server.docs.documents and not server.sync(uri):
        return None
    docs = server.docs
    return _collector_paused(lambda: docs.analyse(uri) if fresh else docs.latest(uri))


def feature(name: str, options: Any = None, empty: Any = None):  # type: ignore[no-untyped-def]
    """Register `fn(params)` for `name`, guarded so that it answers `empty` on failure."""

    def wrap(fn):  # type: ignore[no-untyped-def]
        def handler(ls: LogixServer, params: Any) -> Any:
            return guarded(ls, empty, lambda: fn(params))

        handler.__name__ = fn.__name__

        server.feature(name, options)(handler) if options is not None else server.feature(name)(
            handler
        )
        return fn

    return wrap


def _configure(settings: Any) -> None:
    if not isinstance(settings, dict):
        return
    section = settings.get("logixst", settings)
    if isinstance(section, dict) and "tags" in section:
        tags = section["tags"]
        server.docs.tags_path = str(tags) if tags else None
        for uri in list(server.docs.documents):
            server.schedule(uri)


@server.feature(t.INITIALIZE)
def initialize(ls: LogixServer, params: t.InitializeParams) -> None:
    guarded(ls, None, lambda: _fast_documents(ls))
    guarded(ls, None, lambda: _configure(params.initialization_options))


@server.feature(t.WORKSPACE_DID_CHANGE_CONFIGURATION)
def did_change_configuration(ls: LogixServer, params: t.DidChangeConfigurationParams) -> None:
    guarded(ls, None, lambda: _configure(params.settings))


@server.feature(t.TEXT_DOCUMENT_DID_OPEN)
def did_open(ls: LogixServer, params: t.DidOpenTextDocumentParams) -> None:
    uri = params.text_document.uri
    if language_of(uri_to_path(uri)) is None:
        return
    ls.docs.open(uri, params.text_document.text, params.text_document.version)
    ls.publish(uri)


@server.feature(t.TEXT_DOCUMENT_DID_CHANGE)
def did_change(ls: LogixServer, params: t.DidChangeTextDocumentParams) -> None:
    uri = params.text_document.uri
    if uri in ls.docs.documents and ls.sync(uri):
        ls.schedule(uri)


@server.feature(t.TEXT_DOCUMENT_DID_SAVE)
def did_save(ls: LogixServer, params: t.DidSaveTextDocumentParams) -> None:
    for uri in list(ls.docs.documents):  # a saved sibling changes what the others see
        ls.schedule(uri)


@server.feature(t.TEXT_DOCUMENT_DID_CLOSE)
def did_close(ls: LogixServer, params: t.DidCloseTextDocumentParams) -> None:
    uri = params.text_document.uri
    handle = ls.pending.pop(uri, None)
    if handle is not None:
        handle.cancel()
    ls.docs.close(uri)
    ls.refusals.pop(uri, None)
    ls.text_document_publish_diagnostics(t.PublishDiagnosticsParams(uri=uri, diagnostics=[]))


def _range(span: n.Span) -> t.Range:
    return t.Range(
        t.Position(max(span.line - 1, 0), max(span.col - 1, 0)),
        t.Position(max(span.end_line - 1, 0), max(span.end_col - 1, 0)),
    )


def _location(loc: Location) -> t.Location:
    from pathlib import Path

    return t.Location(uri=Path(loc.path).resolve().as_uri(), range=_range(loc.span))


@feature(
    t.TEXT_DOCUMENT_COMPLETION,
    t.CompletionOptions(trigger_characters=[".", "(", ",", " "]),
    empty=[],
)
def completion(params: t.CompletionParams) -> t.CompletionList | list[Any]:
    an = _analysed(params.text_document.uri)
    if an is None:
        return []
    items, incomplete = comp.complete_list(an, params.position.line, params.position.character)
    return t.CompletionList(
        is_incomplete=incomplete,
        items=[
            t.CompletionItem(
                label=i.label,
                kind=t.CompletionItemKind(i.kind),
                detail=i.detail or None,
                documentation=t.MarkupContent(t.MarkupKind.Markdown, i.documentation)
                if i.documentation
                else None,
                insert_text=i.insert_text,
                insert_text_format=t.InsertTextFormat.Snippet if i.snippet else None,
                sort_text=f"{i.sort}{i.label.lower()}",
            )
            for i in items
        ],
    )


@feature(t.TEXT_DOCUMENT_HOVER)
def hover_(params: t.HoverParams) -> t.Hover | None:
    an = _analysed(params.text_document.uri)
    if an is None:
        return None
    md = hover(an, params.position.line, params.position.character)
    return t.Hover(t.MarkupContent(t.MarkupKind.Markdown, md)) if md else None


@feature(
    t.TEXT_DOCUMENT_SIGNATURE_HELP,
    t.SignatureHelpOptions(trigger_characters=["(", ","], retrigger_characters=[","]),
)
def signature_help(params: t.SignatureHelpParams) -> t.SignatureHelp | None:
    an = _analysed(params.text_document.uri)
    if an is None:
        return None
    sig = signature(an, params.position.line, params.position.character)
    if sig is None:
        return None
    info = t.SignatureInformation(
        label=sig.label,
        documentation=t.MarkupContent(t.MarkupKind.Markdown, sig.documentation),
        parameters=[
            t.ParameterInformation(label=span, documentation=doc)
            for span, (_, doc) in zip(_parameter_spans(sig), sig.parameters, strict=True)
        ],
    )
    return t.SignatureHelp(signatures=[info], active_signature=0, active_parameter=sig.active)


def _parameter_spans(sig: Signature) -> list[tuple[int, int]]:
    """Each operand's [start, end) in the label. A name alone would be highlighted where it
    first occurs: MAS's `DecelJerk` inside `ChangeDecelJerk`, MCD's `Speed` in `ChangeSpeed`."""
    spans, at = [], sig.label.find("(") + 1
    for name, _ in sig.parameters:
        start = sig.label.index(name, at)
        spans.append((start, start + len(name)))
        at = start + len(name)
    return spans


@feature(t.TEXT_DOCUMENT_DEFINITION, empty=[])
def goto_definition(params: t.DefinitionParams) -> list[t.Location]:
    an = _analysed(params.text_document.uri, fresh=True)
    if an is None:
        return []
    return [_location(x) for x in definition(an, params.position.line, params.position.character)]


@feature(t.TEXT_DOCUMENT_REFERENCES, empty=[])
def find_references(params: t.ReferenceParams) -> list[t.Location]:
    an = _analysed(params.text_document.uri, fresh=True)
    if an is None:
        return []
    found = references(
        an, params.position.line, params.position.character, params.context.include_declaration
    )
    return [_location(x) for x in found]


@server.feature(t.TEXT_DOCUMENT_RENAME)
def rename_(ls: LogixServer, params: t.RenameParams) -> t.WorkspaceEdit | None:
    from pygls.exceptions import JsonRpcInvalidRequest

    an = _analysed(params.text_document.uri, fresh=True)
    if an is None:
        return None
    editable = {d.path for d in ls.docs.documents.values() if d.language in ("st", "rll")}
    try:
        places = rename(
            an, params.position.line, params.position.character, params.new_name, editable
        )
    except RenameRefused as exc:
        raise JsonRpcInvalidRequest(str(exc)) from None
    except Exception:  # noqa: BLE001
        ls.log(f"logixst: internal error\n{traceback.format_exc()}", t.MessageType.Error)
        return None
    changes: dict[str, list[t.TextEdit]] = {}
    for loc in places:
        changes.setdefault(_location(loc).uri, []).append(
            t.TextEdit(_range(loc.span), params.new_name)
        )
    return t.WorkspaceEdit(changes=changes)


def _symbol(s: Symbol) -> t.DocumentSymbol:
    r = _range(s.span)
    return t.DocumentSymbol(
        name=s.name,
        kind=t.SymbolKind(s.kind),
        range=r,
        selection_range=r,
        detail=s.detail or None,
        children=[_symbol(c) for c in s.children],
    )


@feature(t.TEXT_DOCUMENT_DOCUMENT_SYMBOL, empty=[])
def doc_symbols(params: t.DocumentSymbolParams) -> list[t.DocumentSymbol]:
    an = _analysed(params.text_document.uri)
    if an is None:
        return []
    return [_symbol(s) for s in document_symbols(an)]


@feature(t.WORKSPACE_SYMBOL, empty=[])
def workspace_symbols(params: t.WorkspaceSymbolParams) -> list[t.WorkspaceSymbol]:
    from pathlib import Path

    query = params.query.lower()
    out: list[t.WorkspaceSymbol] = []
    for uri in list(server.docs.documents):
        an = server.docs.analyse(uri)
        if an is None:
            continue
        stack = list(document_symbols(an))
        while stack:
            s = stack.pop()
            stack.extend(s.children)
            if query in s.name.lower():
                loc = t.Location(
                    uri=Path(an.document.path).resolve().as_uri(), range=_range(s.span)
                )
                out.append(t.WorkspaceSymbol(name=s.name, kind=t.SymbolKind(s.kind), location=loc))
    return out


@feature(t.TEXT_DOCUMENT_FOLDING_RANGE, empty=[])
def folding(params: t.FoldingRangeParams) -> list[t.FoldingRange]:
    an = _analysed(params.text_document.uri)
    if an is None:
        return []
    return [
        t.FoldingRange(
            start_line=a - 1,
            end_line=b - 1,
            kind=t.FoldingRangeKind.Comment if kind == "comment" else t.FoldingRangeKind.Region,
        )
        for a, b, kind in folding_ranges(an)
    ]


@feature(
    t.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL,
    t.SemanticTokensLegend(token_types=list(LEGEND), token_modifiers=[]),
)
def tokens_full(params: t.SemanticTokensParams) -> t.SemanticTokens:
    an = _analysed(params.text_document.uri)
    if an is None:
        return t.SemanticTokens(data=[])
    return t.SemanticTokens(data=encode(semantic_tokens(an)))


@feature(
    t.TEXT_DOCUMENT_CODE_ACTION,
    t.CodeActionOptions(code_action_kinds=[t.CodeActionKind.QuickFix]),
    empty=[],
)
def code_actions(params: t.CodeActionParams) -> list[t.CodeAction]:
    an = _analysed(params.text_document.uri)
    if an is None:
        return []
    uri = params.text_document.uri
    out = []
    for d in params.context.diagnostics:
        r = d.range
        span = n.Span(r.start.line + 1, r.start.character + 1, r.end.line + 1, r.end.character + 1)
        for a in actions(an, str(d.code or ""), d.message, span):
            edits = [t.TextEdit(_range(e.span), e.text) for e in a.edits]
            out.append(
                t.CodeAction(
                    title=a.title,
                    kind=t.CodeActionKind.QuickFix,
                    diagnostics=[d],
                    edit=t.WorkspaceEdit(changes={uri: edits}),
                )
            )
    return out


def run(tcp: str | None = None) -> None:
    """Serve on stdio, or on TCP `HOST:PORT`."""
    if tcp:
        host, _, port = tcp.rpartition(":")
        server.start_tcp(host or "127.0.0.1", int(port))
    else:
        server.start_io()
