from setuptools import find_packages, setup

package_name = 'demo_nodes_py'

setup(
    name=package_name,
    version='0.33.5',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml', 'README.md']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description="The official ROS 2 demos' Python nodes the tutorials run.",
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'talker = demo_nodes_py.topics.talker:main',
            'listener = demo_nodes_py.topics.listener:main',
            'add_two_ints_server = demo_nodes_py.services.add_two_ints_server:main',
            'add_two_ints_client = demo_nodes_py.services.add_two_ints_client:main',
            'add_two_ints_client_async = demo_nodes_py.services.add_two_ints_client_async:main',
            'introspection = demo_nodes_py.services.introspection:main',
        ],
    },
)
