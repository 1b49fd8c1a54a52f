"""Bundles: a project and the files it reads, packed so that a worker without the shared folder
can render it. The project's paths are rewritten to the bundle's own names, so absolute paths
(a probe under /usr/share, say) travel too."""

import hashlib
import io
import json
import os
import shutil
import tarfile
import tempfile
from pathlib import Path

PROJECT_NAME = "project.json"


def input_fields(doc):
    """Yields (field, holder, key) for every file path the project reads, as diffphoton's own
    for_each_input lists them: photo, probe, and the meshes and textures of real proxies and
    virtual objects. `field` names it as a person would look it up: "objects[1].shape.path"."""
    for section in ("photo", "probe"):
        if isinstance(doc.get(section), dict) and doc[section].get("path"):
            yield f"{section}.path", doc[section], "path"
    for group in ("real", "objects"):
        items = doc.get(group)
        for index, item in enumerate(items if isinstance(items, list) else []):
            if not isinstance(item, dict):
                continue
            shape = item.get("shape")
            if isinstance(shape, dict) and shape.get("type") == "mesh" and shape.get("path"):
                yield f"{group}[{index}].shape.path", shape, "path"
            material = item.get("material")
            albedos = [("albedo", item.get("albedo")),
                       ("material.albedo", material.get("albedo") if isinstance(material, dict) else None)]
            for name, albedo in albedos:
                if isinstance(albedo, dict) and albedo.get("texture"):
                    yield f"{group}[{index}].{name}.texture", albedo, "texture"


def _companions(path):
    """Files a mesh reads beside itself: those sharing its stem (an OBJ's .mtl, a glTF's .bin)."""
    folder = path.parent
    try:
        return sorted(p for p in folder.iterdir() if p.is_file() and p.stem == path.stem and p != path)
    except OSError:
        return []


def make_bundle(project_path):
    """Packs the project and its inputs into tar bytes; returns (bytes, sha256 hex)."""
    project_path = Path(project_path).resolve()
    doc = json.loads(project_path.read_text())
    base = project_path.parent
    files = {}  # name in the bundle -> file on this machine
    for _, holder, key in input_fields(doc):
        source = Path(holder[key])
        if not source.is_absolute():
            source = base / source
        if not source.is_file():
            raise FileNotFoundError(f"{project_path}: {holder[key]} (a file the project reads) does not exist")
        # A numbered folder per input: two inputs with the same name in different folders stay apart.
        folder = f"inputs/{len(files)}"
        files[f"{folder}/{source.name}"] = source
        for extra in _companions(source):
            files[f"{folder}/{extra.name}"] = extra
        holder[key] = f"{folder}/{source.name}"
    buffer = io.BytesIO()
    with tarfile.open(fileobj=buffer, mode="w") as tar:
        text = json.dumps(doc, indent=2).encode()
        info = tarfile.TarInfo(PROJECT_NAME)
        info.size = len(text)
        tar.addfile(info, io.BytesIO(text))
        for name, source in sorted(files.items()):
            tar.add(str(source), arcname=name, recursive=False)
    data = buffer.getvalue()
    return data, hashlib.sha256(data).hexdigest()


def unpack_bundle(data, digest, root=None):
    """Unpacks a bundle once per machine into a folder named by its digest (later shards reuse
    it); returns the project file's path there."""
    root = Path(root or os.environ.get("DIFFPHOTON_FARM_CACHE") or Path(tempfile.gettempdir()) / "diffphoton-farm")
    target = root / digest
    project = target / PROJECT_NAME
    if project.is_file():
        return str(project)
    root.mkdir(parents=True, exist_ok=True)
    # Unpacked beside and renamed: two worker processes on one machine never see half a bundle.
    staging = Path(tempfile.mkdtemp(dir=root, prefix=".unpack-"))
    with tarfile.open(fileobj=io.BytesIO(data), mode="r") as tar:
        for member in tar.getmembers():
            if not member.isfile() or member.name.startswith("/") or ".." in Path(member.name).parts:
                raise ValueError(f"bundle {digest}: unexpected entry {member.name!r}")
        try:
            tar.extractall(staging, filter="data")
        except TypeError:  # a Python without extraction filters (before 3.11.4); checked above
            tar.extractall(staging)
    try:
        os.rename(staging, target)
    except OSError:  # another process unpacked it first
        shutil.rmtree(staging, ignore_errors=True)
    return str(project)
