"""caustica: a physically based renderer for the hard light, from Python (docs/PYTHON.md).

    import caustica
    scene = caustica.load_scene("scenes/glass-caustic/scene.xml", width=64, height=64)
    image = caustica.render(scene, integrator="sppm", time=10)   # float32 (H, W, 3)

Everything renders in caustica's C++ render session (the extension caustica._caustica); this
package only gives it Python's shape.
"""
from ._caustica import Error, Renderer, Scene, compare, load_scene, read_image, write_image

__all__ = ["Error", "Renderer", "Scene", "load_scene", "render", "read_image", "write_image", "compare",
           "IMAGE_KEY"]

#: The key of the rendered image in the dict render() returns for a render with AOVs.
IMAGE_KEY = "image"


def render(scene, integrator=None, spp=None, time=None, device="auto", seed=None, resolution=None,
           aovs=None, stereo=None, progress=None, threads=None, spp_per_pass=None, **integrator_params):
    """Renders `scene` to its budget and returns the image as a float32 numpy array (H, W, 3).

    With AOVs (aovs="dd:depth,nn:sh_normal", or the scene's aov integrator): a dict with the image
    under IMAGE_KEY ("image") and each AOV layer as an (H, W, C) array under its name.
    With stereo ("off-axis", "parallel", "toe-in" or a dict with mode, interocular, convergence):
    a tuple (left, right) of (H, W, 3) arrays.
    progress(p) is called after every pass with a dict (spp, target, seconds, time_limit); it may
    return False to stop the render there. Ctrl-C raises KeyboardInterrupt after the current pass.
    Further keyword arguments set the integrator's parameters (max_depth=8, photon_count=...).
    Bad values raise caustica.Error with the one-line message the command line prints.
    """
    r = Renderer(scene, integrator=integrator, spp=spp, time=time, device=device, seed=seed,
                 resolution=resolution, aovs=aovs, stereo=stereo, threads=threads,
                 spp_per_pass=spp_per_pass, **integrator_params)
    r.run(progress)
    image = r.develop()
    if not r.has_aovs:
        return image
    layers = r.aovs()
    if IMAGE_KEY in layers:
        raise Error(f"aovs: a layer named '{IMAGE_KEY}' would hide the image in render()'s dict")
    return {IMAGE_KEY: image, **layers}
