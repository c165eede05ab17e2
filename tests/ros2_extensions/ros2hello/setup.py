from setuptools import find_packages, setup

package_name = 'ros2hello'

setup(
    name=package_name,
    version='0.0.1',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description="A third party's `ros2 hello` command (test data).",
    license='Apache-2.0',
    entry_points={
        'ros2cli.command': ['hello = ros2hello.command:HelloCommand'],
        'ros2cli.extension_point': ['ros2hello.verb = ros2cli.verb:VerbExtension'],
        'ros2hello.verb': ['world = ros2hello.verb:WorldVerb'],
    },
)
