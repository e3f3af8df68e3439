"""report.pdf: the verification report a submission can carry, typeset with ReportLab.

Why ReportLab: it is one Debian package (python3-reportlab) that lays out flowing text, tables
that split across pages with their header repeated, images, a table of contents and running
page headers from Python, in the process that already holds the results; LaTeX would add a
TeX installation of several hundred megabytes, a second program to drive and escape for, and
two or three compiler passes to the base-level test run.

The document, in order: a title page (document id, revision, date, software, commit, hashes,
environment and the sign-off block), the contents, scope and pass rule, the summary of
results, the requirement-to-evidence matrix (qa/traceability/requirements.toml against this
run), one section per problem (description and set-up from its problem.toml, figures with
captions and error panels, every check with its numbers, the justifications), the convergence
studies, and the deviations and known limitations (docs/known-limitations.md). Every page
carries the document id and "page N of M".

Fields of summary.json that other parts of the harness may add are shown when present: a
check's tolerance basis, a problem's mutations, the hashes of the inputs.
"""
import hashlib
import io
import os
import platform
import re
import tomllib
from pathlib import Path
from xml.sax.saxutils import escape

import matplotlib
import numpy
from reportlab import Version as REPORTLAB_VERSION
from reportlab.lib import colors
from reportlab.lib.enums import TA_CENTER
from reportlab.lib.pagesizes import A4
from reportlab.lib.styles import ParagraphStyle
from reportlab.lib.units import mm
from reportlab.lib.utils import ImageReader
from reportlab.pdfbase import pdfmetrics
from reportlab.pdfbase.ttfonts import TTFont
from reportlab.pdfgen import canvas as pdfcanvas
from reportlab.platypus import (BaseDocTemplate, CondPageBreak, Frame, Image, KeepTogether, PageBreak,
                                PageTemplate, Paragraph, Spacer, Table, TableStyle, XPreformatted)
from reportlab.platypus.tableofcontents import TableOfContents

from vdec_verify import PASS_RULE
from vdec_verify.figures import ratio_of
from vdec_verify.work_precision import ratio_text

REPOSITORY = Path(__file__).resolve().parents[3]
LIMITATIONS_FILE = REPOSITORY / "docs" / "known-limitations.md"
REQUIREMENTS_FILE = REPOSITORY / "qa" / "traceability" / "requirements.toml"
LOOSE_RATIO = 20.0   # tolerance over error above this is flagged for review (issue 12)
PAGE_WIDTH, PAGE_HEIGHT = A4
MARGIN = 18 * mm
TEXT_WIDTH = PAGE_WIDTH - 2 * MARGIN
STATUS_COLOURS = {"pass": colors.HexColor("#c8f0c8"), "fail": colors.HexColor("#f4b8b8"),
                  "invalid": colors.HexColor("#f8d49a")}


def _fonts():
    """(regular, bold, italic, mono): DejaVu from matplotlib's data, which has the Greek letters and
    symbols the justifications use; ReportLab's built-in Helvetica only where it is missing."""
    folder = Path(matplotlib.get_data_path()) / "fonts" / "ttf"
    names = {"VdecSans": "DejaVuSans.ttf", "VdecSans-Bold": "DejaVuSans-Bold.ttf",
             "VdecSans-Oblique": "DejaVuSans-Oblique.ttf", "VdecMono": "DejaVuSansMono.ttf"}
    if not all((folder / f).is_file() for f in names.values()):
        return "Helvetica", "Helvetica-Bold", "Helvetica-Oblique", "Courier"
    for name, file in names.items():
        if name not in pdfmetrics.getRegisteredFontNames():
            pdfmetrics.registerFont(TTFont(name, str(folder / file)))
    pdfmetrics.registerFontFamily("VdecSans", normal="VdecSans", bold="VdecSans-Bold", italic="VdecSans-Oblique",
                                  boldItalic="VdecSans-Bold")
    return "VdecSans", "VdecSans-Bold", "VdecSans-Oblique", "VdecMono"


REGULAR, BOLD, ITALIC, MONO = _fonts()


def _style(name, **kw):
    base = dict(fontName=REGULAR, fontSize=8.5, leading=10.5)
    base.update(kw)
    return ParagraphStyle(name, **base)


STYLES = {
    "body": _style("body", spaceAfter=4),
    "small": _style("small", fontSize=7, leading=8.5),
    "cell": _style("cell", fontSize=7, leading=8.5),
    "header": _style("header", fontName=BOLD, fontSize=7, leading=8.5),
    "item": _style("item", fontSize=7.5, leading=9.2, leftIndent=10, bulletIndent=2, spaceAfter=1.5),
    "note": _style("note", fontSize=6.5, leading=8, textColor=colors.HexColor("#444444")),
    "caption": _style("caption", fontSize=7.5, leading=9, fontName=ITALIC, spaceBefore=2, spaceAfter=8),
    "h1": _style("h1", fontName=BOLD, fontSize=14, leading=17, spaceBefore=6, spaceAfter=8),
    "h2": _style("h2", fontName=BOLD, fontSize=11, leading=14, spaceBefore=10, spaceAfter=5),
    "h3": _style("h3", fontName=BOLD, fontSize=9, leading=11, spaceBefore=6, spaceAfter=3),
    "title": _style("title", fontName=BOLD, fontSize=22, leading=27, alignment=TA_CENTER, spaceAfter=6),
    "subtitle": _style("subtitle", fontSize=11, leading=14, alignment=TA_CENTER, spaceAfter=14),
    "mono": _style("mono", fontName=MONO, fontSize=6.8, leading=8.2),
    "toc1": _style("toc1", fontSize=9, leading=12, leftIndent=0),
    "toc2": _style("toc2", fontSize=8, leading=10, leftIndent=14),
}


def text(value):
    """Plain text made safe for ReportLab's paragraph markup."""
    return escape("" if value is None else str(value))


def para(value, style="cell"):
    return Paragraph(text(value), STYLES[style])


CELL_TEXT = 400   # characters of a message inside a table row; the rest follows the table


def shortened(value, where):
    """A message for a table cell: a row cannot be taller than a page, so a long one is cut there
    and given in full `where` (the cut is said in the cell)."""
    value = "" if value is None else str(value)
    return value if len(value) <= CELL_TEXT else f"{value[:CELL_TEXT]} ... (in full {where})"


def markup(value, style="body"):
    return Paragraph(value, STYLES[style])


def number(value):
    return "" if value is None else f"{value:.10g}"


def ratio(value):
    return "" if value is None else f"{value:.3e}"


def result_label(metric):
    if metric["pass"]:
        return "PASS"
    return "INVALID" if (metric.get("message") or "").startswith("invalid reference") else "FAIL"


def sha256_of(path):
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return None


class _Heading(Paragraph):
    """A heading that puts itself in the table of contents and the PDF outline."""

    def __init__(self, content, style, level, key):
        super().__init__(content, STYLES[style])
        self.toc_level, self.toc_key, self.toc_text = level, key, re.sub(r"<[^>]+>", "", content)


class _NumberedCanvas(pdfcanvas.Canvas):
    """Writes "page N of M" once M is known: every page is held until the document is saved."""

    def __init__(self, *args, **kwargs):
        self.document_id = kwargs.pop("document_id", "")
        super().__init__(*args, **kwargs)
        self._pages = []

    def showPage(self):
        self._pages.append(dict(self.__dict__))
        self._startPage()

    def save(self):
        total = len(self._pages)
        for state in self._pages:
            self.__dict__.update(state)
            self.setFont(REGULAR, 7)
            self.setFillColor(colors.HexColor("#444444"))
            self.drawString(MARGIN, PAGE_HEIGHT - 11 * mm, self.document_id)
            self.drawRightString(PAGE_WIDTH - MARGIN, PAGE_HEIGHT - 11 * mm, "vdec verification report")
            self.drawString(MARGIN, 10 * mm, self.document_id)
            self.drawRightString(PAGE_WIDTH - MARGIN, 10 * mm, f"page {self._pageNumber} of {total}")
            self.setStrokeColor(colors.HexColor("#999999"))
            self.setLineWidth(0.4)
            self.line(MARGIN, PAGE_HEIGHT - 12.5 * mm, PAGE_WIDTH - MARGIN, PAGE_HEIGHT - 12.5 * mm)
            self.line(MARGIN, 13 * mm, PAGE_WIDTH - MARGIN, 13 * mm)
            super().showPage()
        super().save()


class _Document(BaseDocTemplate):
    def __init__(self, path, **kw):
        super().__init__(str(path), pagesize=A4, leftMargin=MARGIN, rightMargin=MARGIN, topMargin=17 * mm,
                         bottomMargin=17 * mm, **kw)
        frame = Frame(self.leftMargin, self.bottomMargin, self.width, self.height, id="body")
        self.addPageTemplates([PageTemplate(id="page", frames=[frame])])

    def afterFlowable(self, flowable):
        if isinstance(flowable, _Heading):
            self.canv.bookmarkPage(flowable.toc_key)
            self.canv.addOutlineEntry(flowable.toc_text, flowable.toc_key, level=flowable.toc_level)
            self.notify("TOCEntry", (flowable.toc_level, flowable.toc_text, self.page, flowable.toc_key))


def _table(rows, widths, header_rows=1, extra=()):
    """A table that splits across pages and repeats its header; plain strings stay on one line
    (numbers are never wrapped), Paragraphs wrap."""
    rows = [[Paragraph(text(c), STYLES["header"]) if i < header_rows and isinstance(c, str) else c for c in row]
            for i, row in enumerate(rows)]
    table = Table(rows, colWidths=widths, repeatRows=header_rows, splitByRow=1)
    style = [("FONT", (0, 0), (-1, -1), REGULAR, 7), ("FONT", (0, 0), (-1, header_rows - 1), BOLD, 7),
             ("BACKGROUND", (0, 0), (-1, header_rows - 1), colors.HexColor("#e4e4e4")),
             ("GRID", (0, 0), (-1, -1), 0.3, colors.HexColor("#999999")), ("VALIGN", (0, 0), (-1, -1), "TOP"),
             ("LEFTPADDING", (0, 0), (-1, -1), 2.5), ("RIGHTPADDING", (0, 0), (-1, -1), 2.5),
             ("TOPPADDING", (0, 0), (-1, -1), 1.5), ("BOTTOMPADDING", (0, 0), (-1, -1), 2)]
    table.setStyle(TableStyle(style + list(extra)))
    return table


def _key_value_table(pairs, key_width=38 * mm):
    rows = [[para(k, "cell"), v if isinstance(v, Paragraph) else para(v, "cell")] for k, v in pairs]
    table = Table(rows, colWidths=[key_width, TEXT_WIDTH - key_width], splitInRow=1)
    table.setStyle(TableStyle([("GRID", (0, 0), (-1, -1), 0.3, colors.HexColor("#999999")),
                               ("BACKGROUND", (0, 0), (0, -1), colors.HexColor("#eeeeee")),
                               ("VALIGN", (0, 0), (-1, -1), "TOP"),
                               ("TOPPADDING", (0, 0), (-1, -1), 1.5), ("BOTTOMPADDING", (0, 0), (-1, -1), 2)]))
    return table


# ---------------------------------------------------------------- inputs the report reads besides the records

def problem_file(problems_dir, problem_id):
    """The problem's parsed problem.toml and its leading comment (the problem's description), or
    (None, "") when it cannot be read."""
    path = Path(problems_dir) / problem_id / "problem.toml"
    try:
        source = path.read_text(encoding="utf-8")
        data = tomllib.loads(source)
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return None, ""
    paragraphs, current, started = [], [], False
    for line in source.splitlines():
        stripped = line.strip()
        if stripped.startswith("[["):
            break
        if stripped.startswith("#"):
            started = True
            body = stripped.lstrip("#").strip()
            if body and current and current[-1].endswith("_"):
                current[-1] += body    # an identifier broken at its underscore
            elif body:
                current.append(body)
            elif current:
                paragraphs.append(" ".join(current))
                current = []
        elif started and current:
            paragraphs.append(" ".join(current))
            current = []
    if current:
        paragraphs.append(" ".join(current))
    return data, "\n\n".join(paragraphs)


def load_requirements(path=REQUIREMENTS_FILE):
    try:
        return tomllib.loads(Path(path).read_text(encoding="utf-8")).get("requirement", [])
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return None


def load_limitations(path=LIMITATIONS_FILE):
    """[(section, [item markup])] from docs/known-limitations.md: its "## " sections and "- " items
    (continuation lines indented); markdown links become "text (target)"."""
    try:
        lines = Path(path).read_text(encoding="utf-8").splitlines()
    except OSError:
        return None
    sections, items = [], None
    for line in lines:
        if line.startswith("## "):
            items = []
            sections.append((line[3:].strip(), items))
        elif items is not None and line.startswith("- "):
            items.append(line[2:].strip())
        elif items is not None and items and line.startswith("  ") and line.strip():
            items[-1] += " " + line.strip()

    def rendered(item):
        item = text(item)
        item = re.sub(r"\*\*(.+?)\*\*", r"<b>\1</b>", item)
        item = re.sub(r"`(.+?)`", rf'<font name="{MONO}">\1</font>', item)
        return re.sub(r"\[([^\]]+)\]\(([^)]+)\)", lambda m: f"<i>{_doc_target(m.group(2))}</i>", item)

    return [(title, [rendered(i) for i in entries]) for title, entries in sections]


def _doc_target(target):
    """A link of docs/known-limitations.md as a path from the repository root."""
    if "://" in target:
        return target
    return os.path.normpath(os.path.join("docs", target))


def test_groups(tests):
    """The tests of a requirement by suite or module with their counts ("gtest Polygon (2); pytest
    test_cli_end_to_end (1)"): a requirement can have a hundred tests, whose names are in the RTM."""
    groups = {}
    for test in tests:
        kind, _, name = str(test).partition(":")
        group = f"{kind} {name.split('.')[0]}" if name else kind
        groups[group] = groups.get(group, 0) + 1
    return "; ".join(f"{group} ({count})" for group, count in groups.items())


KNOWN_HARNESS = {"git_commit", "git_dirty", "version", "date", "host", "python", "pass_rule", "level",
                 "software_consistent", "software_disagreements"}
KNOWN_SUMMARY = {"schema", "software", "harness", "counts", "problems"}
KNOWN_PROBLEM = {"id", "title", "requirements", "level", "status", "metrics", "runs", "wall_seconds", "cycles",
                 "scene_sha256", "exit_code", "message", "messages", "convergence", "mutations", "work_precision",
                 "work_precision_baseline"}
KNOWN_METRIC = {"quantity", "variant", "extract", "norm", "rtol", "atol", "error", "tolerance", "pass", "numerical",
                "reference", "justification", "message", "plot", "level"}


def leaves(value, prefix=""):
    """[(dotted key, text)] of the scalars in nested dicts and lists: how fields this module does
    not know (added to summary.json by other parts of the harness) are still shown."""
    if isinstance(value, dict):
        return [leaf for key, item in value.items() for leaf in leaves(item, f"{prefix}.{key}" if prefix else str(key))]
    if isinstance(value, list) and any(isinstance(item, (dict, list)) for item in value):
        return [leaf for i, item in enumerate(value) for leaf in leaves(item, f"{prefix}[{i}]")]
    if isinstance(value, list):
        return [(prefix, ", ".join(map(str, value)))]
    return [(prefix, "" if value is None else str(value))]


def extras(record, known):
    return leaves({key: value for key, value in record.items() if key not in known})


def value_cell(value):
    """Hashes in the monospaced font, other values as text."""
    return markup(text(value), "mono") if re.fullmatch(r"[0-9a-f]{40,128}", value) else para(value, "cell")


def environment(software):
    return [("operating system", f"{platform.system()} {platform.release()} ({platform.platform()})"),
            ("compiler of vdec", software.get("compiler", "unknown")),
            ("Python", platform.python_version()), ("numpy", numpy.__version__),
            ("scipy", _version_of("scipy")), ("matplotlib", matplotlib.__version__),
            ("ReportLab", REPORTLAB_VERSION)]


def _version_of(module):
    try:
        return __import__(module).__version__
    except ImportError:
        return "not installed"


def document_id(software, harness):
    """VDEC-VR-<LEVEL>-<first 12 hex digits of the vdec commit>: one id per level and commit."""
    commit = str(software.get("git_commit") or "unknown")[:12]
    return f"VDEC-VR-{str(harness.get('level', 'full')).upper()}-{commit}"


# ---------------------------------------------------------------- sections

class _Builder:
    def __init__(self, records, summary, out, figures, problems_dir, revision):
        self.records, self.summary, self.out = records, summary, Path(out)
        self.problems_dir = Path(problems_dir) if problems_dir else REPOSITORY / "verification" / "problems"
        self.revision = revision
        self.harness, self.software = summary.get("harness", {}), summary.get("software", {})
        self.story, self.figure_count, self.figures_of = [], 0, figures
        self.id = document_id(self.software, self.harness)
        self.published = {p["id"]: p for p in summary.get("problems", [])}

    def heading(self, content, level, key):
        self.story.append(_Heading(content, "h1" if level == 0 else "h2", level, key))

    def figure(self, png, width, caption):
        """A figure and its numbered caption, as the cell content of a figure table."""
        self.figure_count += 1
        w, h = ImageReader(io.BytesIO(png)).getSize()
        image = Image(io.BytesIO(png), width=width, height=width * h / w)
        return [image, markup(f"<b>Figure {self.figure_count}.</b> {caption}", "caption")]

    # title page
    def title_page(self):
        s, h = self.software, self.harness
        passed = sum(r["status"] == "pass" for r in self.records)
        checks = [m for r in self.records for m in r["metrics"]]
        dirty = {True: "yes: uncommitted changes to tracked files", False: "no", None: "unknown"}[h.get("git_dirty")]
        self.story += [Spacer(1, 18 * mm), markup("vdec verification report", "title"),
                       markup("Verification of the distinct element code vdec against closed-form and "
                              "independent reference solutions", "subtitle")]
        pairs = [("document id", self.id), ("revision", self.revision),
                 ("date", h.get("date", "unknown")),
                 ("software", f"vdec {s.get('version', 'unknown')}, build {s.get('build_type', 'unknown')}"),
                 ("vdec commit", s.get("git_commit", "unknown")),
                 ("harness", f"vdec_verify {h.get('version', 'unknown')}, commit {h.get('git_commit', 'unknown')}"),
                 ("uncommitted changes", dirty),
                 ("suite level", f"{h.get('level', 'full')} ({len(self.records)} problems, {len(checks)} checks)"),
                 ("result", f"{passed} of {len(self.records)} problems passed, {len(self.records) - passed} failed; "
                            f"{sum(m['pass'] for m in checks)} of {len(checks)} checks passed")]
        pairs += [("host", h.get("host", "unknown"))] + environment(s)
        for key, value in self.hashes():
            pairs.append((key, value if isinstance(value, Paragraph) else value_cell(value)))
        self.story.append(_key_value_table(pairs))
        for line in h.get("software_disagreements") or []:
            self.story.append(markup(f"<b>Warning:</b> runs by different vdec builds: {text(line)}", "small"))
        self.story += [Spacer(1, 8 * mm), markup("<b>Sign-off</b>", "h3"), self.sign_off(), PageBreak()]

    def hashes(self):
        """SHA-256 of the evidence this document was made from, and of the inputs when the summary lists them."""
        pairs = []
        summary_sha = sha256_of(self.out / "summary.json")
        if summary_sha:
            pairs.append(("summary.json SHA-256", summary_sha))
        for name in ("requirements.toml",):
            digest = sha256_of(REQUIREMENTS_FILE)
            if digest:
                pairs.append((f"{name} SHA-256", digest))
        further = self.further_provenance()
        if len(further) > 12:
            pairs.append(("further provenance", f"{len(further)} entries of summary.json (section 7)"))
        else:
            pairs += [(key, value_cell(value)) for key, value in further]
        return pairs

    def sign_off(self):
        rows = [["role", "name", "signature", "date"]] + [[role, "", "", ""] for role in
                                                           ("prepared", "reviewed", "approved")]
        table = Table(rows, colWidths=[28 * mm, 55 * mm, 55 * mm, TEXT_WIDTH - 138 * mm],
                      rowHeights=[12] + [26] * 3)
        table.setStyle(TableStyle([("FONT", (0, 0), (-1, -1), REGULAR, 8), ("FONT", (0, 0), (-1, 0), BOLD, 8),
                                   ("GRID", (0, 0), (-1, -1), 0.4, colors.black),
                                   ("BACKGROUND", (0, 0), (-1, 0), colors.HexColor("#e4e4e4")),
                                   ("VALIGN", (0, 0), (-1, -1), "TOP")]))
        return table

    def contents(self):
        toc = TableOfContents()
        toc.levelStyles = [STYLES["toc1"], STYLES["toc2"]]
        self.story += [markup("Contents", "h1"), toc, PageBreak()]

    def scope(self):
        self.heading("1 Scope and pass rule", 0, "scope")
        level = self.harness.get("level", "full")
        self.story += [
            markup("This report is the evidence that vdec, at the commit on the title page, reproduces closed-form "
                   "and independently computed reference solutions of its verification problems "
                   "(verification/problems). It is code verification: it shows that the equations of "
                   "NUREG/CR-5429 as documented in docs/models are solved as stated, not that they describe a "
                   "given rock mass (validation). Each problem names the requirements of "
                   "qa/traceability/requirements.toml it demonstrates; section 3 maps every requirement to its "
                   "evidence."),
            markup(f"Suite level: <b>{text(level)}</b>. The base level is the test suite's (each problem at its "
                   "base resolution, run by ctest); the full level adds refinements, sweeps and the full "
                   "convergence studies, and is the evidence the traceability audit reads."),
            markup("Every number is printed as computed; a table that does not fit a page continues on the next "
                   "with its header repeated. Error and tolerance are relative to the reference's scale s as the "
                   "pass rule states; \"tol/err\" is the tolerance over the error, flagged <i>loose</i> above "
                   f"{LOOSE_RATIO:g} for review."),
            markup("The pass rule, as the harness applies it:", "body"),
            XPreformatted(text(PASS_RULE), STYLES["mono"]), PageBreak()]

    def results(self):
        self.heading("2 Summary of results", 0, "results")
        rows = [["problem", "status", "requirements", "checks", "wall s", "message"]]
        extra = []
        for i, r in enumerate(self.records, start=1):
            good = sum(m["pass"] for m in r["metrics"])
            rows.append([para(r["id"]), r["status"].upper(), para(", ".join(r["requirements"])),
                         f"{good}/{len(r['metrics'])}", f"{r['wall_seconds']:.2f}",
                         para(shortened(r["message"], f"in section 4.{i}"), "note")])
            extra.append(("BACKGROUND", (1, i), (1, i), STATUS_COLOURS.get(r["status"], colors.white)))
        self.story += [_table(rows, [38 * mm, 13 * mm, 44 * mm, 11 * mm, 11 * mm, None], extra=extra), PageBreak()]

    def matrix(self):
        self.heading("3 Requirement-to-evidence matrix", 0, "matrix")
        requirements = load_requirements()
        if requirements is None:
            self.story += [markup(f"{text(REQUIREMENTS_FILE)} could not be read."), PageBreak()]
            return
        status = {r["id"]: r["status"] for r in self.records}
        self.story.append(markup(
            "From qa/traceability/requirements.toml. Problems: the verification problems that demonstrate the "
            "requirement, with their result in this report (<i>not run</i>: not part of this level). Tests: the "
            "unit and Python tests named for it, by test suite or module with their number; their names and results "
            "are in the traceability matrix reports/traceability/rtm.html, which the audit writes from "
            "reports/tests/*.xml."))
        rows = [["requirement", "text and source", "problems (result here)", "tests"]]
        for q in requirements:
            problems = [f"{p} ({status[p].upper() if p in status else 'not run'})" for p in q.get("problems", [])]
            rows.append([para(q.get("id", "")), para(f"{q.get('text', '')} [{q.get('source', '')}]", "note"),
                         para("; ".join(problems) or "none", "note"),
                         para(test_groups(q.get("tests", [])) or "none", "note")])
        self.story += [_table(rows, [27 * mm, 66 * mm, 38 * mm, None]), PageBreak()]

    # one section per problem
    def problems(self):
        self.heading("4 Problems", 0, "problems")
        self.story.append(markup("One section per problem: what it shows, how it is set up, its figures, every "
                                 "check with its numbers and the justification of each tolerance."))
        for n, r in enumerate(self.records, start=1):
            self.problem(f"4.{n}", r)

    def problem(self, number, r):
        data, description = problem_file(self.problems_dir, r["id"])
        self.story.append(CondPageBreak(60 * mm))
        self.heading(f"{number} {text(r['id'])}: {r['status'].upper()}", 1, f"problem-{r['id']}")
        self.story.append(markup(f"<b>{text(r['title'])}</b>"))
        self.story.append(markup(f"Requirements: {text(', '.join(r['requirements']))}. Level: "
                                 f"{text(r.get('level'))}. Wall time {r['wall_seconds']:.2f} s, {r['cycles']} cycles."))
        for paragraph in description.split("\n\n") if description else []:
            self.story.append(para(paragraph, "body"))
        self.set_up(r, data)
        if r["message"]:
            self.story.append(markup(f"<b>Message:</b> {text(r['message'])}", "small"))
        numbered = list(enumerate(r["metrics"], start=1))
        self.figures(r)
        self.check_table(r, numbered)
        self.justifications(numbered)
        self.mutations(r)
        if r.get("convergence") is not None:
            self.study_table(r["convergence"])
        if r.get("work_precision_baseline") is not None:
            self.story.append(markup(f"<b>Against the work-precision baseline:</b> "
                                     f"{text(r['work_precision_baseline']['message'])}", "small"))

    def set_up(self, r, data):
        self.story.append(markup("Set-up", "h3"))
        pairs = []
        if data is not None:
            scene = Path(os.path.normpath(self.problems_dir / r["id"] / str(data.get("scene", ""))))
            try:
                scene = scene.resolve().relative_to(REPOSITORY)
            except ValueError:
                pass
            pairs.append(("scene", str(scene)))
            if data.get("overrides"):
                pairs.append(("overrides", "; ".join(data["overrides"])))
        pairs.append(("scene SHA-256", markup(text(r.get("scene_sha256")), "mono")))
        published = self.published.get(r["id"], {})
        pairs += [(key, value_cell(value)) for key, value in extras(published, KNOWN_PROBLEM)]
        self.story.append(_key_value_table(pairs))
        variants = {v.get("name"): v for v in (data or {}).get("variant", [])}
        if r["runs"]:
            self.story.append(Spacer(1, 3))
            rows = [["run", "overrides of the run", "exit (expected)", "stop reason", "cycles", "wall s"]]
            for run in r["runs"]:
                name = run["variant"] or "(base)"
                overrides = "; ".join(variants.get(run["variant"], {}).get("overrides", [])) if run["variant"] else ""
                rows.append([para(name), para(overrides or "-", "note"),
                             f"{run['exit_code']} ({run['expect_exit']})", para(run.get("stop_reason") or "", "note"),
                             "" if run.get("cycles") is None else str(run["cycles"]), f"{run['wall_seconds']:.2f}"])
            self.story.append(_table(rows, [30 * mm, None, 18 * mm, 28 * mm, 16 * mm, 13 * mm]))

    def figures(self, r):
        """The problem's figures (figures.problem_figures, the PNG files of index.html): those of the
        series checks two to a row, the others across the page."""
        figures = self.figures_of.get(r["id"]) or []
        if not figures:
            return
        half = (TEXT_WIDTH - 6 * mm) / 2
        narrow = [self.figure(f["png"], half, text(f["caption"])) for f in figures if not f["wide"]]
        blocks = []
        for i in range(0, len(narrow), 2):
            pair = narrow[i:i + 2] + ([""] if len(narrow[i:i + 2]) == 1 else [])
            grid = Table([pair], colWidths=[half + 3 * mm] * 2)
            grid.setStyle(TableStyle([("VALIGN", (0, 0), (-1, -1), "TOP"), ("LEFTPADDING", (0, 0), (-1, -1), 0),
                                      ("RIGHTPADDING", (0, 0), (-1, -1), 3 * mm)]))
            blocks.append([grid])
        blocks += [self.figure(f["png"], TEXT_WIDTH * 0.9, text(f["caption"])) for f in figures if f["wide"]]
        blocks[0] = [markup("Figures", "h3")] + blocks[0]    # the heading goes with its first figure
        self.story += [KeepTogether(block) for block in blocks]

    def check_table(self, r, numbered):
        self.story.append(markup("Checks", "h3"))
        if not numbered:
            self.story.append(markup("No check could be evaluated; see the message above.", "small"))
            return
        header = ["#", "quantity", "norm", "numerical", "reference", "error", "tolerance", "tol/err", "result"]
        rows, extra, long_notes = [header], [], []
        for i, (n, m) in enumerate(numbered, start=1):
            variant = f"<i>[{text(m['variant'])}]</i> " if m.get("variant") else ""
            notes = [text(shortened(m["message"], "below the table"))] if m.get("message") else []
            if len(m.get("message") or "") > CELL_TEXT:
                long_notes.append(f"<b>#{n}:</b> {text(m['message'])}")
            published = self.published.get(r["id"], {}).get("metrics") or []
            shown = published[n - 1] if n - 1 < len(published) and isinstance(published[n - 1], dict) else m
            notes += [f"{text(key)}: {text(value)}" for key, value in extras(shown, KNOWN_METRIC)]
            cell = [markup(variant + text(m["quantity"]), "cell")]
            if notes:
                cell.append(markup("; ".join(notes), "note"))
            r_value = ratio_of(m)
            slack = "" if r_value in (None, 0.0) else f"{abs(1.0 / r_value):.3g}"
            if r_value not in (None, 0.0) and m["pass"] and abs(1.0 / r_value) > LOOSE_RATIO:
                slack += " loose"
            label = result_label(m)
            rows.append([str(n), cell, str(m["norm"]), number(m["numerical"]), number(m["reference"]),
                         ratio(m["error"]), ratio(m["tolerance"]), para(slack, "cell"), label])
            extra.append(("BACKGROUND", (8, i), (8, i), STATUS_COLOURS["pass" if label == "PASS" else "fail"]))
        widths = [7 * mm, None, 17 * mm, 24 * mm, 24 * mm, 15.5 * mm, 15.5 * mm, 15 * mm, 12 * mm]
        self.story.append(_table(rows, widths, extra=extra + [("ALIGN", (3, 1), (6, -1), "RIGHT"),
                                                              ("FONT", (3, 1), (6, -1), REGULAR, 6.6)]))
        self.story += [markup(note, "small") for note in long_notes]

    def justifications(self, numbered):
        """Each justification once, with the checks that give it."""
        if not numbered:
            return
        groups = {}
        for n, m in numbered:
            groups.setdefault(m.get("justification") or "(none given)", []).append(n)
        self.story.append(markup("Justifications of the tolerances", "h3"))
        for justification, numbers in groups.items():
            which = "#" + ", #".join(map(str, numbers))
            self.story.append(markup(f"<b>{which}:</b> {text(justification)}", "small"))

    def mutations(self, r):
        mutations = self.published.get(r["id"], {}).get("mutations") or r.get("mutations")
        if not mutations:
            return
        self.story.append(markup("Mutations (a correct suite rejects each)", "h3"))
        rows = [["#", "mutation"]]
        for i, mutation in enumerate(mutations, start=1):
            fields = leaves(mutation) if isinstance(mutation, (dict, list)) else [("", str(mutation))]
            rows.append([str(i), para("; ".join(f"{k}: {v}" if k else v for k, v in fields), "cell")])
        self.story.append(_table(rows, [8 * mm, None]))

    def study_table(self, study):
        self.story.append(markup(f"Convergence study of {text(study.get('quantity', ''))}", "h3"))
        fit = set(study.get("fit_levels", []))
        rows = [["level", "h", "error", "numerical", "cycles", "wall s", "fitted"]]
        cycles = study.get("cycles") or [None] * len(study["levels"])
        numerical = study.get("numerical") or [None] * len(study["levels"])
        for name, h, error, value, cyc, seconds in zip(study["levels"], study["h"], study["error"], numerical, cycles,
                                                       study["wall_seconds"]):
            rows.append([para(name), f"{h:.6g}", ratio(error) or "none", number(value),
                         "" if cyc is None else str(cyc), f"{seconds:.3f}", "yes" if name in fit else ""])
        self.story.append(_table(rows, [32 * mm, 22 * mm, 22 * mm, 28 * mm, 20 * mm, 18 * mm, None]))
        self.story.append(markup(text(study.get("message", "")), "small"))

    def studies(self):
        self.heading("5 Convergence studies", 0, "studies")
        rows = [["problem", "quantity", "observed order", "expected", "band", "GCI (fine)", "asymptotic ratio",
                 "result", "error, time ratio to the baseline"]]
        extra = []
        for r in self.records:
            study = r.get("convergence")
            if study is None:
                continue
            observed = study.get("observed_order")
            rows.append([para(r["id"]), para(study.get("quantity", ""), "note"),
                         "none" if observed is None else f"{observed:.3f}", f"{study['expected_order']:g}",
                         f"+- {study['order_tolerance']:g}", ratio(study.get("gci")) or "none",
                         "none" if study.get("asymptotic_ratio") is None else f"{study['asymptotic_ratio']:.3f}",
                         "PASS" if study["pass"] else "FAIL", para(self.baseline_ratios(r), "note")])
            extra.append(("BACKGROUND", (7, len(rows) - 1), (7, len(rows) - 1),
                          STATUS_COLOURS["pass" if study["pass"] else "fail"]))
        if len(rows) == 1:
            self.story.append(markup("No problem of this run has a convergence study."))
            return
        self.story.append(markup(
            "Observed order: least-squares slope of ln(error) against ln(h) over the fitted levels; it passes when "
            "|observed - expected| is within the band. GCI: Roache's Grid Convergence Index of the finest level "
            "from the three finest fitted levels (Celik et al. 2008, Fs = 1.25), a fraction of the finest value; "
            "asymptotic ratio GCI_23 / (r21^p GCI_12), about 1 in the asymptotic range. Each study's levels, "
            "its error-against-h plot and its work-precision plot are in its problem's section. The last column: "
            "this run's error and wall seconds over those of the committed work-precision baseline, at the finest "
            "level both have (above 1: larger or slower than the baseline)."))
        self.story.append(_table(rows, [30 * mm, None, 16 * mm, 14 * mm, 12 * mm, 17 * mm, 17 * mm, 12 * mm, 24 * mm],
                                 extra=extra))

    @staticmethod
    def baseline_ratios(r):
        """The study's two ratios to the work-precision baseline at the finest common level, or why there are none."""
        compared = r.get("work_precision_baseline") or {}
        study = compared.get("study") or {}
        if study.get("common_level") is None:
            return "no baseline entry" if compared.get("commit") is None else "no common level"
        return (f"{ratio_text(study['error_ratio'])}, {ratio_text(study['time_ratio'])} at "
                f"{study['common_level']} ({compared['commit'][:12]})")

    def deviations(self):
        self.story.append(PageBreak())
        self.heading("6 Deviations and known limitations", 0, "deviations")
        self.story.append(markup("Deviations in this run", "h3"))
        items = []
        for r in self.records:
            for n, m in enumerate(r["metrics"], start=1):
                if not m["pass"]:
                    why = m.get("message") or f"error {ratio(m['error'])}, tolerance {ratio(m['tolerance'])}"
                    items.append(f"{text(r['id'])} check #{n}, {text(m['quantity'])}: {result_label(m)} ({text(why)})")
            if r["status"] != "pass" and not any(not m["pass"] for m in r["metrics"]):
                items.append(f"{text(r['id'])}: {r['status'].upper()}: {text(r['message'])}")
        for line in self.harness.get("software_disagreements") or []:
            items.append(f"runs by different vdec builds: {text(line)}")
        if self.harness.get("git_dirty"):
            items.append("the harness ran from a working tree with uncommitted changes: the commit alone does not "
                         "identify the code")
        for item in items or ["None: every check of every problem passed and every run exited as expected."]:
            self.story.append(Paragraph(item, STYLES["item"], bulletText="\u2022"))
        self.story.append(markup("Known limitations", "h3"))
        limitations = load_limitations()
        if limitations is None:
            self.story.append(markup(f"{text(LIMITATIONS_FILE)} could not be read.", "small"))
            return
        self.story.append(markup("What vdec does not do, as its documentation states (docs/known-limitations.md; "
                                 "each item names its source).", "small"))
        for title, entries in limitations:
            self.story.append(markup(f"<b>{text(title)}</b>", "body"))
            self.story += [Paragraph(entry, STYLES["item"], bulletText="\u2022") for entry in entries]

    def further_provenance(self):
        """Fields of summary.json's harness and top level beyond those this module knows (input
        hashes, the problems folder and filter, ...), as (key, text)."""
        return (leaves({k: v for k, v in self.harness.items() if k not in KNOWN_HARNESS}, "harness")
                + extras(self.summary, KNOWN_SUMMARY))

    def inputs(self):
        further = self.further_provenance()
        if len(further) <= 12:
            return
        self.heading("7 Further provenance", 0, "inputs")
        self.story.append(markup("Every further field of summary.json's provenance, as written (hashes are SHA-256)."))
        rows = [["field", "value"]] + [[para(key, "note"), value_cell(value)] for key, value in further]
        self.story.append(_table(rows, [None, 100 * mm]))

    def build(self, path):
        self.title_page()
        self.contents()
        self.scope()
        self.results()
        self.matrix()
        self.problems()
        self.studies()
        self.deviations()
        self.inputs()
        doc = _Document(path, title="vdec verification report", author="vdec_verify",
                        subject=f"{self.id}, vdec {self.software.get('version', '')} "
                                f"commit {self.software.get('git_commit', '')}")
        doc.multiBuild(self.story, canvasmaker=lambda *a, **k: _NumberedCanvas(*a, document_id=self.id, **k))


def write_pdf(records, out, summary, figures, problems_dir=None, revision="1"):
    """Writes OUT/report.pdf from the records of the run, the summary already written and the
    figures of each problem (problem id -> figures.problem_figures)."""
    path = Path(out) / "report.pdf"
    _Builder(records, summary, out, figures, problems_dir, revision).build(path)
    return path
