"""A scene's structure files made absolute, so the scene can be written elsewhere and still bake."""
import os


def with_absolute_files(scene, base):
    """Rewrites the scene's molecule and lipid-patch files, relative to `base`, as absolute paths."""
    base = os.path.abspath(base)
    for mol in scene["molecules"].values():
        mol["file"] = os.path.join(base, mol["file"])
    for membrane in scene.get("membranes", {}).values():
        for patch in ([membrane["lipid_patch"]] if "lipid_patch" in membrane else []) + membrane.get("lipid_mix", []):
            patch["file"] = os.path.join(base, patch["file"])
    return scene
